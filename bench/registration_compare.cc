// Registration side by side, one command: the paper's Table I (four coarse inputs to SAC-IA) and
// Table II (PCA-ICP, F-4PCS-ICP with PCL's FPCS, ours), plus Open3D's FPFH-RANSAC + ICP, on view
// pairs 36-180 degrees apart of synthetic captures (`simtree synth`, with ground truth), or of
// the stand-in scene of the tests. For every pair: the paper's columns (time, RMSE, match rate)
// and the true errors at the tree (rotation, RMS displacement of the true tree points).
//
//   registration_compare --synth-seeds 10 --markdown table.md --json pairs.json
//   registration_compare --captures scene1/ scene2/
//   registration_compare --stand-in tree01.txt --seeds 3
//
// Timings: per pair, everything a method computes for that pair (for ours: preparing both views,
// i.e. normals, trunk, skeleton and features, plus coarse and fine registration). Preprocessing
// (ground, outliers, voxel grid), shared by all methods, is not counted. The load average is
// printed; do not trust timings taken above 1.5.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <open3d/utility/Logging.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "registration/stand_in_scene.h"
#include "registration_pcl.h"
#include "simtree/core/error.h"
#include "simtree/core/tree_json.h"
#include "simtree/eval/registration_metrics.h"
#include "simtree/io/ground_truth.h"
#include "simtree/preprocessing/preprocess.h"
#include "simtree/registration/baselines.h"
#include "simtree/registration/detail/pairwise.h"
#include "simtree/synth/synth.h"

namespace fs = std::filesystem;
using namespace simtree;
using Clock = std::chrono::steady_clock;

namespace {

double Since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// One capture with its truth, preprocessed.
struct Scene {
  std::string label;
  std::vector<preprocessing::PreprocessedView> views;
  std::vector<ViewPose> poses;
  std::vector<Eigen::Vector3d> tree_points;
};

Scene FromCapture(const fs::path& root, const std::string& label) {
  Scene scene;
  scene.label = label;
  scene.views = preprocessing::PreprocessCaptureViews(OpenCapture(root));
  scene.poses = ReadScanPoses(root / "gt" / "scan_poses.json");
  scene.tree_points = eval::TreeSamplePoints(ReadTreeJson(root / "gt" / "tree.json"));
  if (scene.poses.size() != scene.views.size()) {
    throw InputError(root.string(), "gt/scan_poses.json", "expected one pose per view");
  }
  return scene;
}

Scene FromStandIn(const std::string& tree_file, uint64_t seed) {
  Scene scene;
  scene.label = fmt::format("stand-in {} seed {}", tree_file, seed);
  const Tree tree = test::LoadDemoTree(fs::path(SIMTREE_SHARED_DATA_DIR) / "authors-demo" /
                                       "tree_model" / tree_file);
  scene.tree_points = eval::TreeSamplePoints(tree);
  test::StandInOptions options;
  options.seed = seed;
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  scene.poses = test::StandInPoses(hi.z(), options);
  for (size_t v = 0; v < scene.poses.size(); ++v) {
    const RgbdImage image =
        test::RenderStandInView(tree, scene.poses[v].world_from_camera, options, seed * 1000 + v);
    preprocessing::PreprocessedView view;
    view.name = scene.poses[v].name;
    view.result = preprocessing::PreprocessView(preprocessing::DepthToCloud(image), {}, view.name);
    scene.views.push_back(std::move(view));
  }
  return scene;
}

// One method's outcome on one pair.
struct Outcome {
  std::string method;
  std::string scene;
  std::string source, target;
  int gap_deg = 0;       // nearest of 36, 72, 108, 144, 180
  double angle_deg = 0;  // the true turn between the views
  double seconds = 0;
  double rmse_m = 0;      // the paper's RMSE over matched points
  double match_rate = 0;  // the paper's match rate
  eval::PoseError error;
  bool accepted = true;  // for ours: passed its own checks
  // The tree centroid's displacement in the target camera's frame (x right, y down, z forward).
  Eigen::Vector3d centroid_shift = Eigen::Vector3d::Zero();
  // The rotation error split in the world: about the vertical (a turn about the trunk) and across
  // it (a tilt), degrees.
  double yaw_error_deg = 0, tilt_error_deg = 0;
  // The rotation error as a vector (degrees) in the target camera's frame.
  Eigen::Vector3d rotation_error_target = Eigen::Vector3d::Zero();
  const registration::PairResult* checks =
      nullptr;  // for ours: what its checks measured (while `pairs` lives)
};

int GapBin(double angle_deg) {
  return 36 * std::clamp(static_cast<int>(std::lround(angle_deg / 36.0)), 1, 5);
}

struct Summary {
  int pairs = 0;
  double time_ms = 0, rmse_mm = 0, match = 0, rotation_deg = 0, tree_mm = 0, right = 0;
  double accepted_wrong = 0;
};

double Median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

Summary Summarise(const std::vector<Outcome>& outcomes) {
  Summary s;
  std::vector<double> t, r, m, rot, tree;
  int right = 0, accepted_wrong = 0;
  for (const Outcome& o : outcomes) {
    t.push_back(1e3 * o.seconds);
    r.push_back(1e3 * o.rmse_m);
    m.push_back(100 * o.match_rate);
    rot.push_back(o.error.rotation_deg);
    tree.push_back(1e3 * o.error.tree_rms_m);
    right += o.error.Within();
    accepted_wrong += o.accepted && !o.error.Within();
  }
  s.pairs = static_cast<int>(outcomes.size());
  s.time_ms = Median(t);
  s.rmse_mm = Median(r);
  s.match = Median(m);
  s.rotation_deg = Median(rot);
  s.tree_mm = Median(tree);
  s.right = outcomes.empty() ? NAN : 100.0 * right / outcomes.size();
  s.accepted_wrong = accepted_wrong;
  return s;
}

std::string LoadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string one;
  in >> one;
  return one;
}

// Ours' options as they come (named once: a temporary of them trips GCC 12's
// -Wmaybe-uninitialized in their vectors' destructors).
const registration::PairOptions kDefaultPairOptions;

// The command line.
struct BenchArgs {
  int synth_seeds = 0, stand_in_seeds = 0, first_seed = 1, table1_scenes = 3;
  int baseline_scenes = 100;
  std::string species = "acer_rubrum", stand_in = "tree01.txt", json_path, markdown_path;
  std::vector<std::string> captures;
  fs::path cache = fs::temp_directory_path() / "simtree_registration_bench";
  bool skip_baselines = false, skip_table1 = false, ablations = false, fine_study = false;
  bool views_only = false, skip_paper = false, fine_from_truth = false, old_medial = false;
  double screen_below_overlap = kDefaultPairOptions.screen_below_overlap;
  std::vector<std::string> only_pairs;
};

void AddOptions(CLI::App& app, BenchArgs& a) {
  app.add_option("--synth-seeds", a.synth_seeds,
                 "Synthetic captures to make (seeds from --first-seed)");
  app.add_option("--first-seed", a.first_seed, "First seed")->capture_default_str();
  app.add_option("--species", a.species, "Species of the synthetic trees")->capture_default_str();
  app.add_option("--captures", a.captures, "Capture folders with gt/ (e.g. from `simtree synth`)");
  app.add_option("--stand-in", a.stand_in, "Authors' tree for the stand-in scene")
      ->capture_default_str();
  app.add_option("--seeds", a.stand_in_seeds, "Stand-in scenes to make");
  app.add_option("--cache", a.cache, "Where synthetic captures are kept between runs")
      ->capture_default_str();
  app.add_option("--table1-scenes", a.table1_scenes,
                 "Scenes Table I runs on (its entire-tree row is slow)")
      ->capture_default_str();
  app.add_option("--baseline-scenes", a.baseline_scenes, "Scenes the baselines run on")
      ->capture_default_str();
  app.add_flag("--skip-baselines", a.skip_baselines, "Ours only");
  app.add_flag("--skip-table1", a.skip_table1, "No Table I");
  app.add_flag("--skip-paper", a.skip_paper, "No \"ours without priors\" row");
  app.add_option("--screen-below", a.screen_below_overlap,
                 "Ours: run the turn screen only for results overlapping less than this")
      ->capture_default_str();
  app.add_option("--pairs", a.only_pairs,
                 "Only these pairs, as source:target view indices (e.g. 7:1), in every scene");
  app.add_flag("--ablations", a.ablations, "Ours with each prior left out in turn");
  app.add_flag("--fine-study", a.fine_study,
               "Fine stages (ours, ours without priors, Open3D's ICP) from the same starts");
  app.add_flag("--fine-from-truth", a.fine_from_truth,
               "Only ours' fine stages (variants of it) from the true pose: no full registration, "
               "no coarse start, no Open3D ICP");
  app.add_flag("--old-medial", a.old_medial,
               "Ours with the axis points from the normal lines only and the medial fit a shift "
               "(no rotation)");
  app.add_flag("--views", a.views_only,
               "Each view's trunk and key region in the world frame (by the truth), no pairs");
  app.add_option("--json", a.json_path, "Every pair's outcome as JSON");
  app.add_option("--markdown", a.markdown_path, "The tables as markdown");
}

// The synthetic captures (made once, kept in the cache), the captures given and the stand-in
// scenes.
std::vector<Scene> MakeScenes(const BenchArgs& a) {
  std::vector<Scene> scenes;
  for (int s = 0; s < a.synth_seeds; ++s) {
    const uint64_t seed = a.first_seed + s;
    const fs::path dir = a.cache / fmt::format("{}_seed{}", a.species, seed);
    if (!fs::exists(dir / "gt" / "scan_poses.json")) {
      synth::SynthOptions options;
      options.species = a.species;
      options.seed = seed;
      options.duration_s = 4.5;  // the pull stream is not used here: just past its release
      options.contact_sheet = false;
      fmt::print(stderr, "synth {} seed {} -> {}\n", a.species, seed, dir.string());
      synth::RunSynth(options, dir);
    }
    scenes.push_back(FromCapture(dir, fmt::format("synth {} seed {}", a.species, seed)));
  }
  for (const std::string& c : a.captures) scenes.push_back(FromCapture(c, c));
  for (int s = 0; s < a.stand_in_seeds; ++s) {
    scenes.push_back(FromStandIn(a.stand_in, a.first_seed + s));
  }
  return scenes;
}

// Every method's outcome on every pair, scored against the truth.
class Recorder {
 public:
  explicit Recorder(const registration::PairOptions& match_options)
      : match_options_(match_options) {}

  void Record(const Scene& scene, size_t s, size_t t, const std::string& method,
              const Eigen::Isometry3d& transform, double seconds,
              const registration::RegistrationView& vs, const registration::RegistrationView& vt,
              bool accepted) {
    Outcome o;
    o.method = method;
    o.scene = scene.label;
    o.source = scene.views[s].name;
    o.target = scene.views[t].name;
    const Eigen::Isometry3d& world_from_s = scene.poses[s].world_from_camera;
    const Eigen::Isometry3d& world_from_t = scene.poses[t].world_from_camera;
    o.angle_deg = eval::ViewAngleDeg(world_from_s, world_from_t);
    o.gap_deg = GapBin(o.angle_deg);
    o.seconds = seconds;
    const registration::Overlap match = registration::PaperMatch(vs, vt, transform, match_options_);
    o.rmse_m = match.rmse_m;
    o.match_rate = match.share;
    o.error = eval::PairPoseError(transform, world_from_s, world_from_t, scene.tree_points);
    o.accepted = accepted;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : scene.tree_points) centroid += p;
    centroid /= std::max<double>(1.0, static_cast<double>(scene.tree_points.size()));
    const Eigen::Isometry3d target_from_world = world_from_t.inverse();
    o.centroid_shift =
        transform * (world_from_s.inverse() * centroid) - target_from_world * centroid;
    const Eigen::AngleAxisd world_error(
        (world_from_t * transform * world_from_s.inverse()).linear());
    const Eigen::Vector3d error_vector =
        world_error.angle() * world_error.axis() * 180.0 / std::numbers::pi;
    o.yaw_error_deg = error_vector.z();
    o.tilt_error_deg = error_vector.head<2>().norm();
    const Eigen::AngleAxisd target_error(
        (transform * (target_from_world * world_from_s).inverse()).linear());
    o.rotation_error_target = target_error.angle() * target_error.axis() * 180.0 / std::numbers::pi;
    outcomes_.push_back(o);
  }
  // Ours' checks, for the JSON (`result` must outlive the recorder).
  void AttachChecks(const registration::PairResult* result) { outcomes_.back().checks = result; }
  const std::vector<Outcome>& outcomes() const { return outcomes_; }

 private:
  registration::PairOptions match_options_;
  std::vector<Outcome> outcomes_;
};

// A scene's views prepared for registration, and the time each took.
struct PreparedViews {
  std::vector<registration::RegistrationView> views;
  std::vector<double> seconds;
};

PreparedViews Prepare(const Scene& scene, const registration::RegistrationViewOptions& options) {
  const size_t n = scene.views.size();
  PreparedViews prepared;
  prepared.views.resize(n);
  prepared.seconds.assign(n, 0.0);
  for (size_t v = 0; v < n; ++v) {
    if (!scene.views[v].result) {
      prepared.views[v].name = scene.views[v].name;
      prepared.views[v].failure = scene.views[v].failure;
      continue;
    }
    const auto start = Clock::now();
    prepared.views[v] =
        registration::PrepareView(scene.views[v].name, *scene.views[v].result, options);
    prepared.seconds[v] = Since(start);
  }
  return prepared;
}

// Each view's trunk and key region in the world frame (by the truth): a trunk or key region
// found wrong in one view stands out, the others agree.
void PrintViews(const Scene& scene, const std::vector<registration::RegistrationView>& views) {
  for (size_t v = 0; v < views.size(); ++v) {
    const registration::RegistrationView& view = views[v];
    if (!view.trunk || !view.key_region) {
      fmt::print("{} {}: {}\n", scene.label, view.name, view.failure);
      continue;
    }
    const Eigen::Isometry3d& w = scene.poses[v].world_from_camera;
    const Eigen::Vector3d base = w * view.trunk->base;
    const Eigen::Vector3d fork = w * view.trunk->branch_point;
    const Eigen::Vector3d key = w * view.key_region->center;
    const Eigen::Vector3d axis = w.linear() * registration::TrunkAxis(view);
    double ground_z = std::numeric_limits<double>::quiet_NaN();
    if (view.ground) {
      ground_z = (w * (view.trunk->base -
                       view.ground->SignedDistance(view.trunk->base) * view.ground->normal))
                     .z();
    }
    fmt::print(
        "{} {}: base ({:.3f} {:.3f} {:.3f}) fork ({:.3f} {:.3f} {:.3f}) found {} key "
        "({:.3f} {:.3f} {:.3f}) r {:.2f} axis tilt {:.1f} deg cylinder {} ground z {:.3f} fork "
        "above ground {:.3f} above base {:.3f} coarse {}\n",
        scene.label, view.name, base.x(), base.y(), base.z(), fork.x(), fork.y(), fork.z(),
        view.trunk->fork_found, key.x(), key.y(), key.z(), view.key_region->radius_m,
        std::acos(std::clamp(axis.z(), -1.0, 1.0)) * 180.0 / std::numbers::pi,
        view.trunk->cylinder.has_value(), ground_z,
        registration::HeightOf(view, view.trunk->branch_point, true),
        registration::HeightOf(view, view.trunk->branch_point, false), view.coarse.points_.size());
  }
}

// Every pair of a scene's views (source after target), or those --pairs names.
std::vector<std::pair<size_t, size_t>> ScenePairs(size_t n,
                                                  const std::vector<std::string>& only_pairs) {
  std::vector<std::pair<size_t, size_t>> pairs;
  for (size_t s = 0; s < n; ++s) {
    for (size_t t = s + 1; t < n; ++t) {
      const std::string name = fmt::format("{}:{}", t, s);
      if (only_pairs.empty() ||
          std::find(only_pairs.begin(), only_pairs.end(), name) != only_pairs.end()) {
        pairs.emplace_back(t, s);
      }
    }
  }
  return pairs;
}

// One scene's runs: what every method needs.
struct SceneRun {
  const Scene& scene;
  const PreparedViews& ours;  // the views as ours prepares them
  std::vector<std::pair<size_t, size_t>> pairs;
  registration::PairOptions options;        // ours
  registration::PairOptions paper_options;  // ours without priors: the paper's method as written
  registration::RegistrationViewOptions view_options;
  Recorder& recorder;

  Eigen::Isometry3d Truth(size_t s, size_t t) const {
    return scene.poses[t].world_from_camera.inverse() * scene.poses[s].world_from_camera;
  }
  double PrepSeconds(size_t s, size_t t) const { return ours.seconds[s] + ours.seconds[t]; }
};

registration::PairOptions WithoutPriors(registration::PairOptions o) {
  o.up_prior = o.center_prior = o.snap_to_priors = false;
  o.trunk_axis_weight = o.ground_weight = 0.0;
  o.retry_other_key_regions = o.retry_with_shifts = false;
  return o;
}

// Ours on every pair, and ours without the priors (same code otherwise).
void RunOurs(const SceneRun& run, bool skip_paper,
             std::deque<registration::PairResult>& ours_results) {
  const auto& v = run.ours.views;
  for (const auto& [s, t] : run.pairs) {
    const registration::PairResult& r =
        ours_results.emplace_back(registration::RegisterPair(v[s], v[t], run.options));
    run.recorder.Record(run.scene, s, t, "ours", r.target_from_source,
                        run.PrepSeconds(s, t) + r.seconds, v[s], v[t], r.ok());
    run.recorder.AttachChecks(&r);
    if (skip_paper) continue;
    const registration::PairResult p = registration::RegisterPair(v[s], v[t], run.paper_options);
    run.recorder.Record(run.scene, s, t, "ours without priors", p.target_from_source,
                        run.PrepSeconds(s, t) + p.seconds, v[s], v[t], p.ok());
  }
}

// Which prior helps and which hurts (an uneven ground is not one plane from every side): each
// left out, or (those off by default) put back, in turn.
void RunAblations(const SceneRun& run) {
  std::vector<std::pair<std::string, registration::PairOptions>> variants;
  auto add = [&](const std::string& name, auto change) {
    registration::PairOptions o = run.options;
    change(o);
    variants.emplace_back("ours, " + name, o);
  };
  add("ground as up", [](registration::PairOptions& o) { o.ground_as_up = true; });
  add("ground constraint", [](registration::PairOptions& o) { o.ground_weight = 0.5; });
  add("trunk constraint", [](registration::PairOptions& o) { o.trunk_axis_weight = 1.0; });
  add("no snap", [](registration::PairOptions& o) { o.snap_to_priors = false; });
  add("no turned alternative", [](registration::PairOptions& o) { o.turned_refinements = 0; });
  const auto& v = run.ours.views;
  for (const auto& [s, t] : run.pairs) {
    for (const auto& [name, options] : variants) {
      const registration::PairResult r = registration::RegisterPair(v[s], v[t], options);
      run.recorder.Record(run.scene, s, t, name, r.target_from_source,
                          run.PrepSeconds(s, t) + r.seconds, v[s], v[t], r.ok());
    }
  }
}

// Ours' fine stage and variants of it from the true pose: what is left of the error there is
// the fine stage's own bias.
void RunFineFromTruth(const SceneRun& run) {
  registration::RegistrationViewOptions normal_lines_options = run.view_options;
  normal_lines_options.projection.silhouette = false;
  const PreparedViews normal_lines = Prepare(run.scene, normal_lines_options);
  struct Variant {
    std::string name;
    registration::PairOptions options;
    const std::vector<registration::RegistrationView>* views;
  };
  std::vector<Variant> variants = {{"", run.options, &run.ours.views}};
  auto add = [&](const std::string& name, bool silhouette, auto change) {
    registration::PairOptions o = run.options;
    change(o);
    variants.push_back({", " + name, o, silhouette ? &run.ours.views : &normal_lines.views});
  };
  add("one way", true, [](registration::PairOptions& o) { o.symmetric_fine = false; });
  add("symmetric objective", true, [](registration::PairOptions& o) {
    o.icp.objective = registration::IcpObjective::kSymmetric;
  });
  add("medial shift only", true, [](registration::PairOptions& o) { o.medial.rotation = false; });
  add("normal-line axis points", false, [](registration::PairOptions&) {});
  add("normal-line axis points, medial shift only", false,
      [](registration::PairOptions& o) { o.medial.rotation = false; });
  add("normal-line axis points, medial shift only, one way", false,
      [](registration::PairOptions& o) {
        o.medial.rotation = false;
        o.symmetric_fine = false;
      });
  add("normal-line axis points, medial shift only, symmetric objective", false,
      [](registration::PairOptions& o) {
        o.medial.rotation = false;
        o.icp.objective = registration::IcpObjective::kSymmetric;
      });
  const auto& ours = run.ours.views;
  for (const auto& [s, t] : run.pairs) {
    if (!ours[s].CanRegister() || !ours[t].CanRegister()) continue;
    for (const Variant& variant : variants) {
      const registration::RegistrationView& vs = (*variant.views)[s];
      const registration::RegistrationView& vt = (*variant.views)[t];
      const auto begin = Clock::now();
      registration::FineResult fine =
          registration::RefinePair(vs, vt, run.Truth(s, t), variant.options);
      if (variant.options.symmetric_fine) {
        fine = registration::AverageWithReverse(vs, vt, fine, variant.options);
      }
      run.recorder.Record(run.scene, s, t, "ours' fine" + variant.name + " from truth",
                          fine.icp.target_from_source, Since(begin), ours[s], ours[t], true);
    }
  }
}

// The fine stage isolated: ours' and the baselines' ICP from the same starts (the truth, and
// ours' coarse result), so a difference at the tree is the fine stage's own.
void RunFineStudy(const SceneRun& run) {
  registration::PairOptions coarse_only = run.options;
  coarse_only.run_icp = false;
  std::vector<std::pair<std::string, registration::PairOptions>> variants = {
      {"", run.options}, {" without priors", run.paper_options}};
  auto add_variant = [&](const std::string& name, auto change) {
    registration::PairOptions o = run.paper_options;
    change(o);
    variants.emplace_back(" without priors, " + name, o);
  };
  auto add_ours = [&](const std::string& name, auto change) {
    registration::PairOptions o = run.options;
    change(o);
    variants.emplace_back(", " + name, o);
  };
  add_ours("one way", [](registration::PairOptions& o) { o.symmetric_fine = false; });
  add_variant("45-deg normal gate",
              [](registration::PairOptions& o) { o.icp.max_normal_angle_deg = 45; });
  add_variant("no medial shift",
              [](registration::PairOptions& o) { o.medial_distance_factors.clear(); });
  add_variant("trunk constraint", [](registration::PairOptions& o) { o.trunk_axis_weight = 1.0; });
  add_variant("Open3D's settings, no medial shift", [](registration::PairOptions& o) {
    o.icp.huber_share = 0;
    o.icp.max_source_points = 0;
    o.icp.iterations_per_stage = 30;
    o.medial_distance_factors.clear();
  });
  const auto& ours = run.ours.views;
  for (const auto& [s, t] : run.pairs) {
    if (!ours[s].CanRegister() || !ours[t].CanRegister()) continue;
    const registration::PairResult coarse =
        registration::RegisterPair(ours[s], ours[t], coarse_only);
    if (!coarse.coarse.found) continue;
    registration::BaselineOptions o3d;
    o3d.spacing_m = std::max(ours[s].spacing_m, ours[t].spacing_m);
    for (const auto& [start_name, start] : {std::pair{"truth", run.Truth(s, t)},
                                            std::pair{"ours' coarse", coarse.target_from_source}}) {
      const std::string from = std::string(" from ") + start_name;
      run.recorder.Record(run.scene, s, t, std::string("start") + from, start, 0.0, ours[s],
                          ours[t], true);
      for (const auto& [variant, variant_options] : variants) {
        const auto begin = Clock::now();
        registration::FineResult fine =
            registration::RefinePair(ours[s], ours[t], start, variant_options);
        if (variant_options.symmetric_fine) {
          fine = registration::AverageWithReverse(ours[s], ours[t], fine, variant_options);
        }
        run.recorder.Record(run.scene, s, t, "ours' fine" + variant + from,
                            fine.icp.target_from_source, Since(begin), ours[s], ours[t], true);
      }
      const auto begin = Clock::now();
      const Eigen::Isometry3d open3d =
          registration::Open3dIcp(*ours[s].cloud, *ours[t].cloud, start, o3d);
      run.recorder.Record(run.scene, s, t, "Open3D ICP" + from, open3d, Since(begin), ours[s],
                          ours[t], true);
    }
  }
}

// Table I: the four coarse inputs to the paper's SAC-IA (no priors), coarse only.
void RunTable1(const SceneRun& run) {
  registration::PairOptions coarse_only = run.paper_options;
  coarse_only.run_icp = false;
  for (registration::CoarseInput input :
       {registration::CoarseInput::kEntireTree, registration::CoarseInput::kKeyRegion,
        registration::CoarseInput::kTreeSkeleton, registration::CoarseInput::kKeyRegionSkeleton}) {
    registration::RegistrationViewOptions options;
    options.coarse_input = input;
    const PreparedViews prepared = Prepare(run.scene, options);
    const auto& v = prepared.views;
    for (const auto& [s, t] : run.pairs) {
      const registration::PairResult r = registration::RegisterPair(v[s], v[t], coarse_only);
      run.recorder.Record(run.scene, s, t, std::string("table1 ") + ToString(input),
                          r.target_from_source,
                          prepared.seconds[s] + prepared.seconds[t] + r.seconds, run.ours.views[s],
                          run.ours.views[t], r.ok());
    }
  }
}

// Table II's baselines and Open3D's.
void RunBaselines(const SceneRun& run) {
  const auto& ours = run.ours.views;
  for (const auto& [s, t] : run.pairs) {
    if (!ours[s].cloud || !ours[t].cloud) continue;
    registration::BaselineOptions options;
    options.spacing_m = std::max(ours[s].spacing_m, ours[t].spacing_m);
    const auto& cs = *ours[s].cloud;
    const auto& ct = *ours[t].cloud;
    const registration::BaselineResult pca = registration::PcaIcp(cs, ct, options);
    run.recorder.Record(run.scene, s, t, "PCA-ICP", pca.target_from_source, pca.seconds, ours[s],
                        ours[t], true);
    const registration::BaselineResult fpcs = bench::Fpcs4PcsIcp(cs, ct, options);
    run.recorder.Record(run.scene, s, t, "F-4PCS-ICP (PCL)", fpcs.target_from_source, fpcs.seconds,
                        ours[s], ours[t], true);
    const registration::BaselineResult o3d = registration::Open3dFpfhRansacIcp(cs, ct, options);
    run.recorder.Record(run.scene, s, t, "Open3D FPFH-RANSAC+ICP", o3d.target_from_source,
                        o3d.seconds, ours[s], ours[t], true);
  }
}

// The tables: one row per method and angle, one per method over all angles, then how honest
// ours' own checks are.
std::string TablesMarkdown(const std::vector<Outcome>& outcomes, const std::vector<Scene>& scenes,
                           const std::string& load_start) {
  std::map<std::string, std::map<int, std::vector<Outcome>>> by_method;
  for (const Outcome& o : outcomes) by_method[o.method][o.gap_deg].push_back(o);
  std::string md =
      fmt::format("Scenes: {} ({} views each); load average {} at the start, {} at the end.\n\n",
                  scenes.size(), scenes.front().views.size(), load_start, LoadAverage());
  md +=
      "| method | angle | pairs | time (ms) | RMSE (mm) | match rate | rotation error (deg) | tree "
      "RMS (mm) | right (rot < 2 deg, tree < 2 cm) |\n| --- | --- | --- | --- | --- | --- | --- | "
      "--- | --- |\n";
  const std::vector<std::string> order = {"table1 entire_tree",
                                          "table1 key_region",
                                          "table1 tree_skeleton",
                                          "table1 key_region_skeleton",
                                          "PCA-ICP",
                                          "F-4PCS-ICP (PCL)",
                                          "Open3D FPFH-RANSAC+ICP",
                                          "ours without priors",
                                          "ours, ground as up",
                                          "ours, ground constraint",
                                          "ours, trunk constraint",
                                          "ours, no snap",
                                          "ours, no turned alternative",
                                          "ours"};
  std::vector<std::string> methods = order;
  for (const auto& [method, list] : by_method) {
    if (std::find(order.begin(), order.end(), method) == order.end()) methods.push_back(method);
  }
  for (const std::string& method : methods) {
    if (!by_method.count(method)) continue;
    std::vector<Outcome> all;
    for (const auto& [gap, list] : by_method[method]) {
      const Summary s = Summarise(list);
      md += fmt::format(
          "| {} | {} | {} | {:.0f} | {:.2f} | {:.1f}% | {:.2f} | {:.1f} | {:.0f}% |\n", method, gap,
          s.pairs, s.time_ms, s.rmse_mm, s.match, s.rotation_deg, s.tree_mm, s.right);
      all.insert(all.end(), list.begin(), list.end());
    }
    const Summary s = Summarise(all);
    md += fmt::format(
        "| **{}** | all | {} | {:.0f} | {:.2f} | {:.1f}% | {:.2f} | {:.1f} | {:.0f}% |\n", method,
        s.pairs, s.time_ms, s.rmse_mm, s.match, s.rotation_deg, s.tree_mm, s.right);
  }
  if (by_method.count("ours")) {
    int accepted = 0, accepted_wrong = 0, rejected_right = 0, total = 0;
    for (const auto& [gap, list] : by_method["ours"]) {
      for (const Outcome& o : list) {
        ++total;
        accepted += o.accepted;
        accepted_wrong += o.accepted && !o.error.Within();
        rejected_right += !o.accepted && o.error.Within();
      }
    }
    md += fmt::format(
        "\nOurs' own checks: {} of {} pairs accepted; {} accepted but wrong by the truth, {} "
        "refused though right.\n",
        accepted, total, accepted_wrong, rejected_right);
  }
  return md;
}

// Every outcome, with what ours' checks measured.
nlohmann::ordered_json OutcomesJson(const std::vector<Outcome>& outcomes) {
  nlohmann::ordered_json doc = nlohmann::ordered_json::array();
  for (const Outcome& o : outcomes) {
    doc.push_back(
        {{"method", o.method},
         {"scene", o.scene},
         {"source", o.source},
         {"target", o.target},
         {"angle_deg", o.angle_deg},
         {"gap_deg", o.gap_deg},
         {"time_ms", 1e3 * o.seconds},
         {"rmse_mm", 1e3 * o.rmse_m},
         {"match_rate", o.match_rate},
         {"rotation_error_deg", o.error.rotation_deg},
         {"tree_rms_mm", 1e3 * o.error.tree_rms_m},
         {"centroid_error_mm", 1e3 * o.error.centroid_m},
         {"centroid_shift_target_mm",
          {1e3 * o.centroid_shift.x(), 1e3 * o.centroid_shift.y(), 1e3 * o.centroid_shift.z()}},
         {"yaw_error_deg", o.yaw_error_deg},
         {"tilt_error_deg", o.tilt_error_deg},
         {"rotation_error_target_deg",
          {o.rotation_error_target.x(), o.rotation_error_target.y(), o.rotation_error_target.z()}},
         {"right", o.error.Within()},
         {"accepted", o.accepted}});
    if (!o.checks) continue;
    nlohmann::ordered_json& j = doc.back();
    j["status"] = o.checks->status;
    j["up_disagreement_deg"] = o.checks->up_disagreement_deg;
    j["ground_offset_mm"] = 1e3 * o.checks->ground_offset_m;
    j["trunk_offset_mm"] = 1e3 * o.checks->trunk_offset_m;
    j["coarse_overlap"] = o.checks->coarse_overlap;
    j["fitness"] = o.checks->fine.fitness;
    j["turned_deg"] = o.checks->turned_deg;
    j["own_key_regions"] = o.checks->own_key_regions;
    j["retried_without_priors"] = o.checks->retried_without_priors;
    j["attempt"] = ToString(o.checks->attempt);
    j["view_overlap"] = o.checks->view_overlap;
    j["shifted_mm"] = 1e3 * o.checks->shifted_m;
    j["medial_shift_mm"] = 1e3 * o.checks->medial_shift_m;
    j["reverse_gap_mm"] = 1e3 * o.checks->reverse_gap_m;
  }
  return doc;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Registration side by side: paper Tables I and II, ours and Open3D, against truth"};
  BenchArgs args;
  AddOptions(app, args);
  CLI11_PARSE(app, argc, argv);
  open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);
  const std::string load_start = LoadAverage();
  const std::vector<Scene> scenes = MakeScenes(args);
  if (scenes.empty()) {
    fmt::print(stderr, "no scenes: give --synth-seeds, --captures or --seeds\n");
    return 2;
  }

  registration::PairOptions options;
  options.screen_below_overlap = args.screen_below_overlap;
  registration::RegistrationViewOptions view_options;
  if (args.old_medial) {
    options.medial.rotation = false;
    view_options.projection.silhouette = false;
  }
  Recorder recorder(options);
  std::deque<registration::PairResult> ours_results;  // what ours' checks measured, for the JSON
  for (size_t k = 0; k < scenes.size(); ++k) {
    const Scene& scene = scenes[k];
    fmt::print(stderr, "{}: {} views\n", scene.label, scene.views.size());
    const PreparedViews ours = Prepare(scene, view_options);
    if (args.views_only) {
      PrintViews(scene, ours.views);
      continue;
    }
    const SceneRun run{scene,
                       ours,
                       ScenePairs(scene.views.size(), args.only_pairs),
                       options,
                       WithoutPriors(kDefaultPairOptions),
                       view_options,
                       recorder};
    if (!args.fine_from_truth) RunOurs(run, args.skip_paper, ours_results);
    if (args.ablations) RunAblations(run);
    if (args.fine_from_truth) RunFineFromTruth(run);
    if (args.fine_study) RunFineStudy(run);
    if (!args.skip_table1 && static_cast<int>(k) < args.table1_scenes) RunTable1(run);
    if (!args.skip_baselines && static_cast<int>(k) < args.baseline_scenes) RunBaselines(run);
  }

  const std::string md = TablesMarkdown(recorder.outcomes(), scenes, load_start);
  fmt::print("{}", md);
  if (!args.markdown_path.empty()) std::ofstream(args.markdown_path) << md;
  if (!args.json_path.empty()) {
    std::ofstream(args.json_path) << OutcomesJson(recorder.outcomes()).dump(1) << "\n";
  }
  return 0;
}
