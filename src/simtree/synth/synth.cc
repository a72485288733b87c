#include "simtree/synth/synth.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>
#include <oneapi/tbb/task_group.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/progress.h"
#include "simtree/core/tree_json.h"
#include "simtree/io/capture.h"
#include "simtree/io/ground_truth.h"
#include "simtree/io/track_init.h"
#include "simtree/io/trajectories.h"
#include "simtree/synth/detail/camera_color.h"
#include "simtree/synth/detail/camera_rig.h"
#include "simtree/synth/detail/contact_sheet.h"
#include "simtree/synth/detail/fem_model.h"
#include "simtree/synth/detail/fem_modes.h"
#include "simtree/synth/detail/fem_response.h"
#include "simtree/synth/detail/fem_truth.h"
#include "simtree/synth/detail/init_clicks.h"
#include "simtree/synth/detail/leaf_occluders.h"
#include "simtree/synth/detail/marker_placement.h"
#include "simtree/synth/detail/pull_rig.h"
#include "simtree/synth/detail/rgbd_renderer.h"
#include "simtree/synth/detail/sensor_model.h"
#include "simtree/synth/detail/sensor_scene.h"
#include "simtree/synth/detail/tree_generator.h"
#include "simtree/synth/detail/tree_pose.h"
#include "simtree/synth/species.h"

namespace fs = std::filesystem;

namespace simtree::synth {
namespace {

using Clock = std::chrono::steady_clock;
double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Seeds of the independent random parts, so changing one part does not reshuffle the others. The
// tree takes the seed itself: `synth --seed 7` grows GenerateTree(species, 7).
enum class Stream : uint64_t {
  kMarkers = 1,
  kScanRig,
  kVibration,
  kScene,
  kScanNoise,
  kPullNoise,
  kInitClicks,
  kCamera,
  kLeaves,
};
uint64_t SeedFor(uint64_t seed, Stream stream) {
  uint64_t z = seed * 0x9E3779B97F4A7C15ull + static_cast<uint64_t>(stream) * 0xBF58476D1CE4E5B9ull;
  z ^= z >> 31;
  return z * 0x94D049BB133111EBull;
}

void CheckOptions(const SynthOptions& o) {
  auto fail = [](const char* field, const std::string& what) {
    throw InputError("synth options", field, what);
  };
  if (o.views < 0 || o.views > 72) fail("views", fmt::format("expected 1-72, got {}", o.views));
  if (!std::isfinite(o.duration_s) || o.duration_s < 0 || o.duration_s > 600) {
    fail("duration_s", fmt::format("expected up to 600 s, got {}", o.duration_s));
  }
  if (!(o.fps >= 1 && o.fps <= 120)) fail("fps", fmt::format("expected 1-120, got {}", o.fps));
  if (o.markers < 1 || o.markers > 100) {
    fail("markers", fmt::format("expected 1-100, got {}", o.markers));
  }
  if (!(o.pull_deflection_m >= 0 && o.pull_deflection_m < 1)) {
    fail("pull_deflection_m",
         fmt::format("expected [0, 1) m (0: automatic), got {}", o.pull_deflection_m));
  }
  if (!(o.pull_deflection_per_length > 0 && o.pull_deflection_per_length <= 0.5)) {
    fail("pull_deflection_per_length",
         fmt::format("expected (0, 0.5], got {}", o.pull_deflection_per_length));
  }
  if (!(o.pull_position >= 0.05 && o.pull_position <= 0.95)) {
    fail("pull_position",
         fmt::format("expected [0.05, 0.95] of the branch's length, got {}", o.pull_position));
  }
  if (!(o.max_pull_rotation_rad > 0 && o.max_pull_rotation_rad <= 0.5)) {
    fail("max_pull_rotation_rad",
         fmt::format("expected (0, 0.5] rad, got {}", o.max_pull_rotation_rad));
  }
  if (!(o.init_click_noise_px >= 0 && o.init_click_noise_px <= 50)) {
    fail("init_click_noise_px", fmt::format("expected 0-50 px, got {}", o.init_click_noise_px));
  }
  if (!(o.min_force_n > 0 && o.max_force_n >= o.min_force_n && std::isfinite(o.max_force_n))) {
    fail("max_force_n", "expected 0 < min_force_n <= max_force_n");
  }
  if (o.HasColorCamera()) AzureColorCamera::ForSize(o.color_width, o.color_height, "color_size");
}

// The pull test a person would set up: a rope round a first-level branch that carries taped
// children (its sub-branches reach the most levels of tapeable thickness, so the pull excites a
// whole chain of links, as in the paper), long and reachable from the ground, tied at
// `SynthOptions::pull_position` of its length, pulled outwards and down towards a stake in the
// ground.
struct PullSetup {
  int branch = -1;
  // The branch's outer part (two thirds of the way out), which chooses it and sets the pull
  // camera's distance to the crown: the markers do not depend on where the rope is tied.
  Eigen::Vector3d crown_point = Eigen::Vector3d::Zero();
  double arc_length = 0.0;  // where the rope is tied
  Eigen::Vector3d attach = Eigen::Vector3d::Zero();
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();
  Eigen::Vector3d outward = Eigen::Vector3d::UnitX();  // horizontal
};

// How many levels below `branch` its sub-branches reach, counting only branches thick enough
// for tape at their base.
std::vector<int> TapeableDepth(const Tree& tree, double min_radius_m) {
  const std::vector<std::vector<int>> children = tree.Children();
  std::vector<int> depth(tree.size(), 0);
  for (int id = tree.size() - 1; id >= 0; --id) {  // children have larger ids
    for (const int c : children[id]) {
      if (tree.branches[c].nodes.front().radius >= min_radius_m) {
        depth[id] = std::max(depth[id], depth[c] + 1);
      }
    }
  }
  return depth;
}

PullSetup ChoosePull(const Tree& tree, double min_tape_radius_m, double pull_position) {
  PullSetup best;
  double best_score = -std::numeric_limits<double>::infinity();
  const std::vector<int> depth = TapeableDepth(tree, min_tape_radius_m);
  for (const Branch& b : tree.branches) {
    if (b.level != 1 || b.nodes.size() < 3) continue;
    const double length = b.Length();
    const Eigen::Vector3d p = b.PointAt(0.65 * length);
    Eigen::Vector3d out(p.x(), p.y(), 0.0);
    if (out.norm() < 0.05) continue;  // straight above the trunk: no room to pull sideways
    // Carrying taped levels first (a level counts as much as a metre of branch), then long and
    // within reach (a person reaches up to about 2.2 m).
    const double reach_penalty = std::max(0.0, p.z() - 2.2);
    const double score = depth[b.id] + length + 0.5 * out.norm() - 3.0 * reach_penalty;
    if (score > best_score) {
      best_score = score;
      best.branch = b.id;
      best.crown_point = p;
      best.outward = out.normalized();
    }
  }
  if (best.branch >= 0) {
    best.arc_length = pull_position * tree.branches[best.branch].Length();
  } else {
    // A tree without usable first-level branches: pull the trunk at two thirds of its height.
    best.branch = 0;
    best.arc_length = 0.66 * tree.trunk().Length();
    best.crown_point = tree.trunk().PointAt(best.arc_length);
    best.outward = Eigen::Vector3d::UnitX();
  }
  best.attach = tree.branches[best.branch].PointAt(best.arc_length);
  // The stake: 2.5 m further out on the ground, so the rope runs outwards and down.
  best.anchor = best.attach + 2.5 * best.outward;
  best.anchor.z() = 0.0;
  return best;
}

MarkerFrame2d ToMarkerFrame(int frame, double time_s, const std::vector<MarkerObservation>& obs) {
  MarkerFrame2d out;
  out.frame = frame;
  out.time_s = time_s;
  for (const MarkerObservation& o : obs) out.markers.push_back(o.box);
  return out;
}

// --hard: a red cool box on the ground, as red as the tape, where the pull camera sees it (the
// ray through the pixel a quarter in from the left and a quarter up from the bottom), so a
// tracker that goes by colour alone finds one more red thing.
SceneBox RedDistractor(const Eigen::Isometry3d& camera, const CameraIntrinsics& k) {
  SceneBox box;
  box.half_extent = Eigen::Vector3d(0.2, 0.15, 0.17);
  box.albedo = Eigen::Vector3f(0.78f, 0.08f, 0.08f);
  const Eigen::Vector3d origin = camera.translation();
  const Eigen::Vector3d ray =
      camera.linear() *
      Eigen::Vector3d((0.25 * k.width - k.cx) / k.fx, (0.75 * k.height - k.cy) / k.fy, 1.0);
  double t = 2.5;  // metres along the ray (z = 1) when it does not come down to the box's top
  if (ray.z() < -1e-3) t = std::clamp((2.0 * box.half_extent.z() - origin.z()) / ray.z(), 1.2, 4.0);
  box.center = origin + t * ray;
  box.center.z() = box.half_extent.z();
  box.yaw_rad = std::atan2(ray.y(), ray.x());
  return box;
}

// The pull's schedule (quick: shorter). Throws InputError when the stream ends before the
// release.
PullLoad MakePullLoad(const PullSetup& pull_setup, double force, double duration, bool quick) {
  PullLoad pull;
  pull.branch = pull_setup.branch;
  pull.arc_length = pull_setup.arc_length;
  pull.attach_point = pull_setup.attach;
  pull.anchor = pull_setup.anchor;
  pull.force_n = force;
  pull.ramp_start_s = quick ? 0.3 : 0.5;
  pull.hold_start_s = quick ? 1.3 : 2.5;
  pull.release_s = quick ? 1.8 : 4.0;
  pull.duration_s = duration;
  if (pull.release_s >= duration) {
    throw InputError(
        "synth options", "duration_s",
        fmt::format("expected a stream longer than the release at {:.1f} s", pull.release_s));
  }
  return pull;
}

struct RopeForce {
  double force_n = 0.0;
  double compliance_m_per_n = 0.0;  // the tied point's static deflection under 1 N
  double rotation_rad_per_n = 0.0;  // the largest rotation of any node under 1 N
};

// The rope's force for the wanted deflection of the tied point, capped so no node turns more than
// the options allow (the FEM is linear), within the options' force range.
RopeForce ChooseRopeForce(const FemModel& model, const Tree& tree, const PullSetup& pull_setup,
                          const SynthOptions& options) {
  RopeForce rope;
  const Eigen::Vector3d rope_direction = (pull_setup.anchor - pull_setup.attach).normalized();
  const Eigen::VectorXd unit_load =
      model.PointLoad(pull_setup.branch, pull_setup.arc_length, rope_direction);
  const Eigen::VectorXd unit_response = SolveStatic(model, unit_load);
  const TreePose unit_pose = model.Pose(unit_response);
  rope.compliance_m_per_n =
      (unit_pose.PointAt(tree, pull_setup.branch, pull_setup.arc_length) - pull_setup.attach)
          .norm();
  for (int node = 1; node < model.node_count(); ++node) {
    rope.rotation_rad_per_n =
        std::max(rope.rotation_rad_per_n, model.NodeMap(node).Apply(unit_response).rotation.norm());
  }
  const double wanted_deflection =
      options.pull_deflection_m > 0
          ? options.pull_deflection_m
          : options.pull_deflection_per_length * tree.branches[pull_setup.branch].Length();
  rope.force_n =
      std::clamp(std::min(wanted_deflection / std::max(rope.compliance_m_per_n, 1e-12),
                          options.max_pull_rotation_rad / std::max(rope.rotation_rad_per_n, 1e-12)),
                 options.min_force_n, options.max_force_n);
  return rope;
}

// The tree of the species and seed; quick: a sparser tree of the same species and depth (half as
// many buds break: 70-190 branches instead of 300-1,500, every level still there), and `species`
// says so.
Tree GrowTree(SpeciesParams& species, const SynthOptions& options) {
  GeneratorOptions generator;
  if (options.quick) {
    species.trunk.buds.break_probability *= 0.5;
    for (LevelParams& level : species.levels) level.buds.break_probability *= 0.5;
    generator.max_branches = 300;
  }
  return GenerateTree(species, options.seed, generator);
}

void ReportTree(const Tree& tree, SynthReport& report) {
  report.branches = tree.size();
  report.nodes = tree.NodeCount();
  report.levels = tree.MaxLevel() + 1;
  report.markers = static_cast<int>(tree.markers.size());
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  report.height_m = hi.z();
}

// The pull's motion by the FEM, the tree's pose at each frame time into `frame_poses`.
PullResult IntegrateFramePoses(const FemModel& model, const ModalBasis& modes, const PullLoad& pull,
                               const std::vector<double>& frame_times,
                               std::vector<TreePose>& frame_poses) {
  NewmarkOptions newmark;
  newmark.sample_rates = false;
  return IntegratePull(
      model, modes, pull, frame_times, newmark,
      [&](int i, double, const FemState& state) { frame_poses[i] = model.Pose(state.x); });
}

// Where tape goes: the first chain down the pulled branch, on bands the pull camera sees at least
// `kMinTapeWidthPx` wide at the crown's distance (a person tapes branches they can see on the
// tablet; thinner twigs would carry markers no tracker finds at 640 x 576).
MarkerPlacementOptions TapePlacement(const SynthOptions& options, const PullSetup& pull_setup,
                                     const Eigen::Isometry3d& pull_camera, double focal_px) {
  MarkerPlacementOptions placement;
  placement.count = options.markers;
  placement.first_chain_branch = pull_setup.branch;  // the pulled branch and its children
  placement.camera_position = pull_camera.translation();
  placement.seed = SeedFor(options.seed, Stream::kMarkers);
  constexpr double kMinTapeWidthPx = 2.0;
  const double crown_distance = (pull_camera.translation() - pull_setup.crown_point).norm();
  placement.min_radius_m =
      std::max(placement.min_radius_m, 0.5 * kMinTapeWidthPx * crown_distance / focal_px);
  return placement;
}

void LogFem(const FemModel& model, const ModalBasis& modes, const PullSetup& pull_setup,
            const RopeForce& rope, const SynthReport& report) {
  spdlog::info(
      "synth: FEM {} dof, {} modes ({:.3f}-{:.2f} Hz); rope on branch {} at {:.2f} m, "
      "{:.1f} N ({:.1f} mm/N): the tied point moves {:.0f} mm, no node turns more than {:.3f} rad",
      model.dof_count(), modes.count(), modes.frequency_hz[0],
      modes.frequency_hz[modes.count() - 1], pull_setup.branch, pull_setup.arc_length, rope.force_n,
      1e3 * rope.compliance_m_per_n, 1e3 * report.pull_deflection_m, report.pull_max_rotation_rad);
}

// The markers the pull camera does not see in its first frame (the tree at rest), by the
// renderer's own test (marker_boxes.h): it also sees the scene's props, how much of each band
// shows and how many pixels it covers, which the placement's line-of-sight test does not. (Twice
// the tracker's thresholds was tried: it moved every level-3 tape off acer_palmatum seed 1.)
std::vector<int> MarkersHiddenAtRest(const Tree& tree, const SensorModel& sensor,
                                     const Eigen::Isometry3d& camera, const SceneOptions& props,
                                     uint64_t noise_seed) {
  const SensorScene scene(tree, props);
  RenderOptions render;
  render.seed = noise_seed;
  render.shadows = false;
  const RenderResult result = RenderRgbd(scene, sensor, camera, render);
  std::vector<int> hidden;
  for (const MarkerObservation& o : result.markers) {
    if (!o.box.visible) hidden.push_back(o.box.id);
  }
  return hidden;
}

struct PullFrameRender {
  uint64_t seed = 0;
  int frame = 0;
  double time_s = 0.0;
  bool leaves = false;  // --hard: leaves swinging in front of markers (leaf_occluders.h)
  uint64_t leaf_seed = 0;
};

// One frame of the pull stream with its marker boxes; with leaves, they are planned on the first
// frame rendered (into `leaves`) and painted in before the boxes are computed, so `visible`
// follows them.
RenderResult RenderPullFrame(const SensorScene& scene, const PullRig& rig,
                             const PullFrameRender& frame, std::vector<LeafOccluder>& leaves) {
  RenderOptions render;
  render.seed = frame.seed;
  render.frame = frame.frame;
  render.marker_boxes = !frame.leaves;
  RenderResult result = RenderPullRig(scene, rig, render);
  if (!frame.leaves) return result;
  const CameraIntrinsics k = rig.Intrinsics();
  const Eigen::Isometry3d camera = rig.WorldFromImage();
  if (frame.frame == 0) {
    const std::vector<MarkerObservation> rest = ComputeMarkerBoxes(scene, k, camera, result.labels);
    // Leaves of the same angular size at any colour size (their sizes are for 640 x 576).
    const double pixel_scale = k.fx / rig.depth_sensor.FocalLengthPx();
    leaves = PlanLeafOccluders(ToMarkerFrame(0, frame.time_s, rest),
                               {.seed = frame.leaf_seed, .pixel_scale = pixel_scale});
  }
  DrawLeafOccluders(leaves, frame.time_s, result.image.color, result.image.depth, result.labels);
  result.markers = ComputeMarkerBoxes(scene, k, camera, result.labels);
  return result;
}

// --hard: the frames where some marker moves more than `min_px` a frame in the image (the swing's
// fastest, after the release), which are rendered with motion blur.
std::vector<bool> FastFrames(const Tree& tree, const std::vector<TreePose>& poses,
                             const Eigen::Isometry3d& camera_from_world, const CameraIntrinsics& k,
                             double min_px = 5.0) {
  const int n = static_cast<int>(poses.size());
  std::vector<bool> fast(n, false);
  const auto pixel = [&](int i, const Marker& m) {
    return k.Project(camera_from_world * poses[i].PointAt(tree, m.branch, m.arc_length));
  };
  for (int i = 1; i + 1 < n; ++i) {
    for (const Marker& m : tree.markers) {
      if (0.5 * (pixel(i + 1, m) - pixel(i - 1, m)).norm() > min_px) fast[i] = true;
    }
  }
  return fast;
}

TreePose Lerp(const TreePose& a, const TreePose& b, double w) {
  TreePose out = a;
  for (int k = 0; k < out.node_count(); ++k) {
    out.positions()[k] += w * (b.positions()[k] - a.positions()[k]);
  }
  return out;
}

// Motion blur over an exposure of half a frame centred on the frame's time: the colour at its two
// ends (the pose a quarter of the way to the previous and to the next frame, the leaves where they
// are then), to be averaged with the frame's own. Leaves the scene in the last end's pose.
std::vector<RgbImage> RenderExposureEnds(SensorScene& scene, const PullRig& rig,
                                         const std::vector<TreePose>& poses,
                                         const PullFrameRender& frame, double frame_interval_s,
                                         const std::vector<LeafOccluder>& leaves) {
  std::vector<RgbImage> ends;
  for (const int side : {-1, 1}) {
    scene.SetPose(Lerp(poses[frame.frame], poses[frame.frame + side], 0.25));
    RenderOptions render;
    render.seed = frame.seed;
    render.frame = frame.frame;
    render.marker_boxes = false;
    // The colour camera's colour only; registered to depth, the same render as ever.
    render.measure_depth = !rig.color;
    RenderResult r = RenderPullRig(scene, rig, render);
    DrawLeafOccluders(leaves, frame.time_s + 0.25 * side * frame_interval_s, r.image.color,
                      r.image.depth, r.labels);
    ends.push_back(std::move(r.image.color));
  }
  return ends;
}

// `color` becomes the mean of itself and `others` (same size).
void AverageColor(const std::vector<RgbImage>& others, RgbImage& color) {
  const double n = 1.0 + static_cast<double>(others.size());
  for (size_t p = 0; p < color.pixels.size(); ++p) {
    double sum = color.pixels[p];
    for (const RgbImage& o : others) sum += o.pixels[p];
    color.pixels[p] = static_cast<uint8_t>(sum / n + 0.5);
  }
}

// Places the markers, then moves those the pull camera does not see at rest (a person tapes what
// they see on the tablet): their sites are excluded and the placement runs again, a few rounds at
// most.
void PlaceVisibleMarkers(Tree& tree, MarkerPlacementOptions& placement, const SensorModel& sensor,
                         const Eigen::Isometry3d& pull_camera, const SceneOptions& scene_options,
                         uint64_t noise_seed) {
  MarkerPlacementResult placed;
  std::vector<int> hidden_at_rest;
  for (int round = 0; round < 4; ++round) {
    placed = PlaceMarkers(tree, placement);
    hidden_at_rest = MarkersHiddenAtRest(tree, sensor, pull_camera, scene_options, noise_seed);
    if (hidden_at_rest.empty()) break;
    for (const int id : hidden_at_rest) {
      placement.excluded_sites.emplace_back(tree.markers[id].branch, tree.markers[id].arc_length);
    }
  }
  std::string per_level;
  for (int count : placed.markers_per_level) per_level += fmt::format(" {}", count);
  spdlog::info(
      "synth: markers on branches of radius >= {:.1f} mm, per level:{}; {} hidden by the "
      "placement's test, {} in the pull camera's first frame",
      1e3 * placement.min_radius_m, per_level, placed.hidden, hidden_at_rest.size());
}

int CountTreePixels(const RenderResult& r) {
  int count = 0;
  for (size_t i = 0; i < r.labels.pixels.size(); ++i) {
    count += r.labels.pixels[i].kind == SurfaceKind::kBranch && r.image.depth.pixels[i] != 0;
  }
  return count;
}

// The static scans, written under `root`: the tree trembles a little between views (wind, the
// person walking). Adds each view to `tiles`; returns the views' poses for gt/.
std::vector<ViewPose> RenderScans(const SynthOptions& options, const Tree& tree,
                                  const FemModel& model, const ModalBasis& modes,
                                  SensorScene& scene, const SensorModel& sensor,
                                  const fs::path& root, std::vector<ContactSheetTile>& tiles,
                                  SynthReport& report) {
  ScanRigOptions rig = options.hard ? ScanRigOptions::Hard() : ScanRigOptions{};
  rig.views = options.views > 0 ? options.views : (options.quick ? 4 : rig.views);
  const std::vector<Eigen::Isometry3d> view_poses =
      ScanViewPoses(tree, rig, SeedFor(options.seed, Stream::kScanRig));
  std::vector<ViewPose> gt_views;
  double tree_pixels = 0;
  {
    Progress progress("synth: scans", static_cast<int64_t>(view_poses.size()), "views");
    for (size_t v = 0; v < view_poses.size(); ++v) {
      VibrationOptions vibration;
      vibration.seed = SeedFor(options.seed, Stream::kVibration) + v;
      scene.SetPose(model.Pose(RandomVibrationState(model, modes, vibration).x));
      RenderOptions render;
      render.seed = SeedFor(options.seed, Stream::kScanNoise);
      render.frame = static_cast<int64_t>(v);
      render.marker_boxes = false;
      RenderResult r = RenderRgbd(scene, sensor, view_poses[v], render);
      const std::string name = fmt::format("view_{:02d}", v);
      WriteScanView(root, name, r.image, options.png);
      gt_views.push_back({name, view_poses[v]});
      tree_pixels += CountTreePixels(r);
      tiles.push_back({name, std::move(r.image.color), std::move(r.image.depth)});
      progress.Advance();
    }
  }
  report.views = static_cast<int>(view_poses.size());
  report.tree_pixels_per_view = tree_pixels / std::max<size_t>(1, view_poses.size());
  return gt_views;
}

// capture.json: the sensor and the command that made the capture.
CaptureInfo DescribeCapture(const SynthOptions& options, const std::string& species) {
  CaptureInfo info;
  info.sensor = options.hard ? "synthetic azure_kinect_nfov_unbinned (hard)"
                             : "synthetic azure_kinect_nfov_unbinned";
  const std::string color_size =
      options.HasColorCamera()
          ? fmt::format(" --color-size {}x{}", options.color_width, options.color_height)
          : "";
  if (options.HasColorCamera()) {
    info.sensor += fmt::format(", pull stream colour {}x{} with depth registered to it",
                               options.color_width, options.color_height);
  }
  info.species = species;
  info.notes = fmt::format("simtree synth --species {} --seed {}{}{}{}{}", species, options.seed,
                           options.quick ? " --quick" : "", options.hard ? " --hard" : "",
                           options.clean_color ? " --clean-color" : "", color_size);
  return info;
}

// gt/synth.json: what was made and how long each part took (total: until now).
void WriteSynthSummary(const SynthOptions& options, SynthReport& report, Clock::time_point start,
                       const fs::path& path) {
  report.total_s = SecondsSince(start);
  const nlohmann::ordered_json summary = {
      {"format", "simtree.synth_report"},
      {"version", 1},
      {"species", report.species},
      {"seed", report.seed},
      {"quick", options.quick},
      {"hard", options.hard},
      {"clean_color", options.clean_color},
      {"pull_color_size",
       options.HasColorCamera()
           ? nlohmann::ordered_json::array({options.color_width, options.color_height})
           : nlohmann::ordered_json(nullptr)},
      {"branches", report.branches},
      {"nodes", report.nodes},
      {"levels", report.levels},
      {"height_m", report.height_m},
      {"markers", report.markers},
      {"fem_dof", report.fem_dof},
      {"fem_modes", report.fem_modes},
      {"first_frequency_hz", report.first_frequency_hz},
      {"pull_force_n", report.pull_force_n},
      {"pull_deflection_m", report.pull_deflection_m},
      {"pull_max_rotation_rad", report.pull_max_rotation_rad},
      {"views", report.views},
      {"frames", report.frames},
      {"tree_pixels_per_view", report.tree_pixels_per_view},
      {"seconds",
       {{"tree", report.tree_s},
        {"fem", report.fem_s},
        {"scans", report.scans_s},
        {"pull", report.pull_s},
        {"total", report.total_s}}}};
  WriteFileAtomically(path, summary.dump(1) + "\n");
}

}  // namespace

namespace {

// --truth-only: gt/ with the tree, the pull, the modal truth, the species and synth.json.
void WriteTruthOnly(const SynthOptions& options, const Tree& tree, const PullLoad& pull,
                    const ModalTruth& truth, const SpeciesParams& species, SynthReport& report,
                    Clock::time_point start, const fs::path& out) {
  AtomicDirectory folder(out);
  const fs::path gt = folder.path() / "gt";
  fs::create_directories(gt);
  WriteTreeJson(tree, gt / "tree.json");
  WritePullLoad(pull, gt / "pull_load.json");
  WriteModalTruth(truth, gt / "modal.json");
  WriteSpeciesJson(species, gt / "species.json");
  WriteSynthSummary(options, report, start, gt / "synth.json");
  folder.Commit();
}

// pull/markers.json (the tape and its links) and pull/init.json (the tracker's start as a person
// clicking the markers in the first frame gives it).
void WriteMarkersAndInit(const SynthOptions& options, const Tree& tree,
                         const std::vector<MarkerFrame2d>& boxes,
                         const CameraIntrinsics& intrinsics, const fs::path& pull_dir) {
  std::vector<MarkerLink> links;
  for (const Marker& m : tree.markers) links.push_back({m.id, m.label, m.parent, std::nullopt});
  WriteMarkersJson(links, pull_dir / "markers.json");
  WriteTrackInitJson(SimulateInitClicks(boxes, intrinsics.width, intrinsics.height,
                                        {.noise_px = options.init_click_noise_px,
                                         .seed = SeedFor(options.seed, Stream::kInitClicks)}),
                     pull_dir / "init.json");
}

struct PullStreamOutput {
  std::vector<PullFrame> frames;
  std::vector<MarkerFrame2d> boxes;  // gt/markers_2d.json
  Trajectories trajectories;         // gt/trajectories.csv
};

// The pull-test stream from the tripod, written to `pull_dir`. Frames render one after another
// (each uses both cores); the camera's colour pipeline runs on each, and PNG encoding and writing
// of a frame overlap the next frame's rendering. Frees each of `frame_poses` once rendered; adds
// the contact sheet's pull frames to `tiles`.
PullStreamOutput RenderPullStream(const SynthOptions& options, const Tree& tree, SensorScene& scene,
                                  const PullRig& rig, const PullLoad& pull,
                                  const std::vector<double>& frame_times,
                                  std::vector<TreePose>& frame_poses, const fs::path& pull_dir,
                                  std::vector<ContactSheetTile>& tiles) {
  const int frame_count = static_cast<int>(frame_times.size());
  const double duration = pull.duration_s;
  PullStreamOutput out;
  out.frames.resize(frame_count);
  out.boxes.resize(frame_count);
  Trajectories& trajectories = out.trajectories;
  for (const Marker& m : tree.markers) trajectories.tracks.push_back(MarkerTrack{m.id, {}, {}});
  const Eigen::Isometry3d camera_from_world = rig.WorldFromImage().inverse();
  const int release_frame =
      std::min(frame_count - 1, static_cast<int>(std::ceil(pull.release_s * options.fps)));
  const std::vector<int> sheet_frames = {0, release_frame - 1,
                                         std::min(frame_count - 1, release_frame + 8)};
  // The colour camera: its white balance and exposure drift for the whole record; --hard: the
  // light drops by 0.8 EV a little after the release (a cloud) and the exposure follows.
  const CameraColor color_camera(
      options.hard
          ? CameraColorOptions::WithExposureStep(pull.release_s + 0.4 * (duration - pull.release_s))
          : CameraColorOptions{},
      SeedFor(options.seed, Stream::kCamera));
  {
    Progress progress("synth: pull stream", frame_count, "frames");
    oneapi::tbb::task_group writers;
    std::vector<LeafOccluder> leaves;  // --hard: planned on the first frame
    const std::vector<bool> blurred =
        options.hard ? FastFrames(tree, frame_poses, camera_from_world, rig.Intrinsics())
                     : std::vector<bool>(frame_count, false);
    if (options.hard) {
      spdlog::info("synth: {} of {} pull frames with motion blur (a marker moves > 5 px a frame)",
                   std::count(blurred.begin(), blurred.end(), true), frame_count);
    }
    for (int i = 0; i < frame_count; ++i) {
      if (frame_times[i] < pull.release_s) {
        scene.SetRope(RopeSegment{pull.branch, pull.arc_length, pull.anchor});
      } else {
        scene.SetRope(std::nullopt);
      }
      const PullFrameRender render{.seed = SeedFor(options.seed, Stream::kPullNoise),
                                   .frame = i,
                                   .time_s = frame_times[i],
                                   .leaves = options.hard,
                                   .leaf_seed = SeedFor(options.seed, Stream::kLeaves)};
      std::vector<RgbImage> streak;  // --hard, at the swing's fastest: the exposure's ends
      if (blurred[i]) {
        streak = RenderExposureEnds(scene, rig, frame_poses, render, 1.0 / options.fps, leaves);
      }
      scene.SetPose(frame_poses[i]);
      auto result = std::make_shared<RenderResult>(RenderPullFrame(scene, rig, render, leaves));
      if (!streak.empty()) AverageColor(streak, result->image.color);
      if (!options.clean_color) color_camera.Apply(frame_times[i], i, result->image.color);
      // Ground truth: the marker centres on the deformed branch axis, camera frame.
      std::vector<Eigen::Vector3d> centres;
      for (const Marker& m : tree.markers) {
        centres.push_back(camera_from_world * frame_poses[i].PointAt(tree, m.branch, m.arc_length));
      }
      trajectories.AddFrame(i, frame_times[i], centres,
                            std::vector<bool>(tree.markers.size(), true));
      out.boxes[i] = ToMarkerFrame(i, frame_times[i], result->markers);
      if (options.contact_sheet &&
          std::find(sheet_frames.begin(), sheet_frames.end(), i) != sheet_frames.end()) {
        const char* what = i == 0 ? "start" : (i < release_frame ? "held" : "after release");
        tiles.push_back(
            {fmt::format("pull frame {} ({})", i, what), result->image.color, result->image.depth});
      }
      if (i > 0) frame_poses[i - 1] = TreePose();  // rendered (and blurred with): free it
      writers.run([&, i, result] {
        out.frames[i] = WritePullFrame(pull_dir, i, frame_times[i], result->image.color,
                                       result->image.depth, options.png);
        progress.Advance();
      });
    }
    writers.wait();
  }
  return out;
}

// The tripod. With a colour camera of its own, the person frames the tree on the colour preview:
// the colour camera takes PullCameraPose's aim and the depth camera sits beside it (4.9 degrees
// lower); the stream's images and ground truth are in the colour camera's frame.
PullRig MakePullRig(const SynthOptions& options, const Eigen::Isometry3d& pull_camera,
                    const SensorModel& sensor) {
  PullRig rig{.world_from_depth = pull_camera, .depth_sensor = sensor, .color = std::nullopt};
  if (options.HasColorCamera()) {
    rig.color = AzureColorCamera::ForSize(options.color_width, options.color_height);
    rig.world_from_depth = pull_camera * rig.color->color_from_depth;
  }
  return rig;
}

// The lowest 100 modes reach 8-15 Hz on the presets; the modal integration adds the static
// response of the rest, and their share of any marker's motion after release is far below the
// sensor's noise. Asking for every mode below 20 Hz instead costs 300+ modes and ~20x the time.
ModalBasis ComputeSynthModes(const FemModel& model) {
  ModesOptions modes_options;
  modes_options.count = 100;
  return ComputeModes(model, modes_options);
}

// The stream's frame times: i / fps for every frame that starts within `duration_s`.
std::vector<double> FrameTimes(double duration_s, double fps) {
  const int frame_count = static_cast<int>(std::floor(duration_s * fps + 1e-9));
  std::vector<double> times(frame_count);
  for (int i = 0; i < frame_count; ++i) times[i] = i / fps;
  return times;
}

}  // namespace

std::string SynthReport::Summary() const {
  return fmt::format(
      "{} seed {}: {} branches, {} nodes, {} levels, {:.2f} m tall, {} markers; FEM {} dof, {} "
      "modes, first {:.3f} Hz; pull on branch {} with {:.1f} N ({:.0f} mm, up to {:.3f} rad), "
      "released at {:.2f} s; {} views, {} pull frames; {:.1f} s (tree {:.1f}, FEM {:.1f}, scans "
      "{:.1f}, pull {:.1f})",
      species, seed, branches, nodes, levels, height_m, markers, fem_dof, fem_modes,
      first_frequency_hz, pull_branch, pull_force_n, 1e3 * pull_deflection_m, pull_max_rotation_rad,
      pull_release_s, views, frames, total_s, tree_s, fem_s, scans_s, pull_s);
}

SynthReport RunSynth(const SynthOptions& options, const fs::path& out) {
  CheckOptions(options);
  const Clock::time_point start = Clock::now();
  SynthReport report;
  report.seed = options.seed;

  // ---- 1. The tree and its markers.
  SpeciesParams species = options.species_file.empty() ? SpeciesPreset(options.species)
                                                       : ReadSpeciesJson(options.species_file);
  report.species = species.name;
  Tree tree = GrowTree(species, options);
  const PullSetup pull_setup =
      ChoosePull(tree, MarkerPlacementOptions{}.min_radius_m, options.pull_position);
  const Eigen::Isometry3d pull_camera = PullCameraPose(tree, pull_setup.outward);
  const SensorModel sensor = options.hard ? SensorModel::Hard() : SensorModel::AzureKinectNfov();
  const PullRig rig = MakePullRig(options, pull_camera, sensor);
  MarkerPlacementOptions placement =
      TapePlacement(options, pull_setup, pull_camera, sensor.FocalLengthPx());
  SceneOptions scene_options =
      DefaultSceneOptions(tree, SeedFor(options.seed, Stream::kScene), options.hard);
  if (options.hard) {
    scene_options.boxes.push_back(RedDistractor(rig.WorldFromImage(), rig.Intrinsics()));
  }
  // Tapes the stream's camera sees at rest (the colour camera's view is 59 degrees high, and 32 mm
  // of parallax changes what hides a band at the edge of visibility).
  PlaceVisibleMarkers(tree, placement, rig.ImageSensor(), rig.WorldFromImage(), scene_options,
                      SeedFor(options.seed, Stream::kPullNoise));
  tree.metadata.source = fmt::format("synth {} seed {}", species.name, options.seed);
  ReportTree(tree, report);
  report.tree_s = SecondsSince(start);
  spdlog::info("synth: {} seed {}: {} branches, {} nodes, {} levels, {:.2f} m, {} markers",
               species.name, options.seed, report.branches, report.nodes, report.levels,
               report.height_m, report.markers);

  // ---- 2. The FEM oracle: modes, and the rope's force for the wanted deflection.
  const Clock::time_point fem_start = Clock::now();
  const FemModel model(tree, species.wood.Properties(), SpeciesFemOptions(species));
  const ModalBasis modes = ComputeSynthModes(model);
  report.fem_dof = model.dof_count();
  report.fem_modes = modes.count();
  report.first_frequency_hz = modes.frequency_hz[0];
  const RopeForce rope = ChooseRopeForce(model, tree, pull_setup, options);
  const double force = rope.force_n;
  report.pull_deflection_m = force * rope.compliance_m_per_n;
  report.pull_max_rotation_rad = force * rope.rotation_rad_per_n;
  LogFem(model, modes, pull_setup, rope, report);

  // The pull's schedule: still, a slow ramp (well over a period, so the hold starts nearly at
  // rest), a hold, the cut, then the free decay to the end of the stream.
  const double duration =
      options.duration_s > 0 ? options.duration_s : (options.quick ? 5.0 : 15.0);
  const PullLoad pull = MakePullLoad(pull_setup, force, duration, options.quick);
  report.pull_branch = pull.branch;
  report.pull_force_n = force;
  report.pull_release_s = pull.release_s;

  const std::vector<double> frame_times = FrameTimes(duration, options.fps);
  const int frame_count = static_cast<int>(frame_times.size());
  std::vector<TreePose> frame_poses(frame_count);
  const PullResult pull_run = IntegrateFramePoses(model, modes, pull, frame_times, frame_poses);
  ModalTruthOptions truth_options;
  truth_options.record_after_release_s = duration - pull.release_s;
  const ModalTruth truth =
      ComputeModalTruth(model, modes, tree, pull_run.release_state, truth_options);
  report.fem_s = SecondsSince(fem_start);
  if (options.truth_only) {
    WriteTruthOnly(options, tree, pull, truth, species, report, start, out);
    return report;
  }

  // ---- 3. The sensor and the scene.
  const CameraIntrinsics intrinsics = rig.Intrinsics();
  SensorScene scene(tree, scene_options);

  AtomicDirectory folder(out);
  const fs::path root = folder.path();
  fs::create_directories(root / "scans");
  fs::create_directories(root / "pull");
  fs::create_directories(root / "gt");
  std::vector<ContactSheetTile> tiles;

  // ---- 4. Static scans: the tree trembles a little between views (wind, the person walking).
  const Clock::time_point scans_start = Clock::now();
  const std::vector<ViewPose> gt_views =
      RenderScans(options, tree, model, modes, scene, sensor, root, tiles, report);
  report.scans_s = SecondsSince(scans_start);

  // ---- 5. The pull-test stream from the tripod, and the tracker's start.
  const Clock::time_point pull_start = Clock::now();
  const fs::path pull_dir = root / "pull";
  WriteIntrinsicsJson(intrinsics, pull_dir / "intrinsics.json");
  const PullStreamOutput stream =
      RenderPullStream(options, tree, scene, rig, pull, frame_times, frame_poses, pull_dir, tiles);
  const std::vector<MarkerFrame2d>& boxes = stream.boxes;
  const Trajectories& trajectories = stream.trajectories;
  WriteFramesCsv(stream.frames, pull_dir / "frames.csv");
  WriteMarkersAndInit(options, tree, boxes, intrinsics, pull_dir);
  report.frames = frame_count;
  report.pull_s = SecondsSince(pull_start);

  // ---- 6. Ground truth and the description.
  const fs::path gt = root / "gt";
  WriteTreeJson(tree, gt / "tree.json");
  WriteScanPoses(gt_views, gt / "scan_poses.json");
  WritePullCamera(rig.WorldFromImage(), gt / "pull_camera.json");
  WritePullLoad(pull, gt / "pull_load.json");
  WriteTrajectoriesCsv(trajectories, gt / "trajectories.csv");
  WriteMarkers2d(boxes, gt / "markers_2d.json");
  WriteModalTruth(truth, gt / "modal.json");
  WriteSpeciesJson(species, gt / "species.json");
  WriteCaptureInfo(DescribeCapture(options, species.name), root / "capture.json");
  if (options.contact_sheet) WritePng(MakeContactSheet(tiles), root / "contact_sheet.png");

  WriteSynthSummary(options, report, start, gt / "synth.json");
  folder.Commit();
  return report;
}

}  // namespace simtree::synth
