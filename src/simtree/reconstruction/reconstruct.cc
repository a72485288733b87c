#include "simtree/reconstruction/reconstruct.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/core/validate.h"
#include "simtree/reconstruction/detail/geodesic_samples.h"
#include "simtree/reconstruction/detail/point_index.h"
#include "simtree/reconstruction/detail/scan_graph.h"
#include "simtree/reconstruction/detail/voxel_grid.h"

namespace simtree::reconstruction {
namespace {

class Stopwatch {
 public:
  double Lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// The tree's points and the lengths measured on them.
struct TreePoints {
  std::vector<Eigen::Vector3d> points;  // the prepared cloud without ground and sparse returns
  GroundPlane ground;
  size_t sparse_removed = 0;
  CloudScale measured;        // of `points`
  ReconstructionScale scale;  // derived from `measured` where options.scale has zeros
};

// A scene cloud (a merged Kinect capture) is mostly ground: the ground goes first, on every
// point, so that it decides neither the spacing nor the working voxels, and the scale is measured
// again on what stands on it.
TreePoints SeparateFromGround(std::vector<Eigen::Vector3d> prepared,
                              const ReconstructionOptions& options) {
  TreePoints tree;
  tree.measured = MeasureCloudScale(prepared, {.seed = options.seed});
  tree.scale = DeriveScale(tree.measured, options.scale, options.band_per_link);
  if (options.remove_ground) {
    GroundOptions ground_options = options.ground;
    ground_options.tolerance_m = std::max(ground_options.tolerance_m, tree.scale.trunk_threshold_m);
    tree.ground = FindGroundPlane(prepared, ground_options, options.seed);
    spdlog::debug(
        "ground: {} ({} points up to {:.3f} m, plane {:.2f} m wide, {:.2f} m standing on it, "
        "{:.0f}% covered)",
        tree.ground.found ? "found" : "none", tree.ground.ground_points, tree.ground.clearance_m,
        tree.ground.plane_width_m, tree.ground.standing_width_m, 100 * tree.ground.covered_share);
  }
  if (!tree.ground.found) {
    tree.points = std::move(prepared);
    return tree;
  }
  std::vector<Eigen::Vector3d> above_ground;
  above_ground.reserve(prepared.size() - tree.ground.ground_points);
  for (size_t i = 0; i < prepared.size(); ++i) {
    if (!tree.ground.is_ground[i]) above_ground.push_back(prepared[i]);
  }
  if (options.clean_scene) {
    // Sparse returns: fewer neighbours than a surface seen at the measured spacing has.
    SparseReturnOptions sparse_options;
    sparse_options.radius_m = std::max(4.0 * tree.measured.spacing_m, 0.01);
    const std::vector<char> sparse = FindSparseReturns(above_ground, sparse_options);
    std::erase_if(above_ground,
                  [&](const Eigen::Vector3d& p) { return sparse[&p - above_ground.data()] != 0; });
    tree.sparse_removed = static_cast<size_t>(std::count(sparse.begin(), sparse.end(), 1));
  }
  if (above_ground.size() >= 10) {
    tree.measured = MeasureCloudScale(above_ground, {.seed = options.seed});
    tree.scale = DeriveScale(tree.measured, options.scale, options.band_per_link);
  }
  tree.points = std::move(above_ground);
  return tree;
}

// The points every later step works on: the tree's points averaged per voxel.
struct WorkingCloud {
  std::vector<Eigen::Vector3d> points;
  ReconstructionScale scale;  // the lengths used (a coarser voxel rederives them)
  size_t object_points_removed = 0;
};

// Voxel means, at a coarser voxel when there would be more than max_working_points; on a scene,
// without the objects that stand on the ground apart from the tree (boxes, posts). Throws
// InputError naming `source` when fewer than 10 are left.
WorkingCloud MakeWorkingCloud(const TreePoints& tree, const std::string& source,
                              const ReconstructionOptions& options) {
  WorkingCloud working;
  working.scale = tree.scale;
  double voxel = tree.scale.voxel_m;
  working.points = VoxelAverageAtMost(tree.points, options.max_working_points, &voxel);
  if (voxel > tree.scale.voxel_m * 1.001) {
    ReconstructionScale given = options.scale;
    given.voxel_m = voxel;
    working.scale = DeriveScale(tree.measured, given, options.band_per_link);
  }
  const ReconstructionScale& s = working.scale;
  spdlog::debug(
      "scale: spacing {:.4f} roughness {:.4f}; voxel {:.4f} neighbours {:.4f} band {:.4f} "
      "step {:.4f} influence {:.4f} kill {:.4f} gap {:.3f} trunk {:.4f}",
      tree.measured.spacing_m, tree.measured.roughness_m, s.voxel_m, s.neighbour_radius_m,
      s.band_width_m, s.step_m, s.influence_radius_m, s.kill_radius_m, s.max_gap_m,
      s.trunk_threshold_m);
  if (tree.ground.found && options.clean_scene) {
    const std::vector<char> object = FindObjectsOnGround(
        working.points, tree.ground,
        {.neighbour_radius_m = s.neighbour_radius_m, .touch_height_m = s.band_width_m});
    std::vector<Eigen::Vector3d> kept;
    kept.reserve(working.points.size());
    for (size_t i = 0; i < working.points.size(); ++i) {
      if (!object[i]) kept.push_back(working.points[i]);
    }
    working.object_points_removed = working.points.size() - kept.size();
    working.points = std::move(kept);
    spdlog::debug("scene: {} sparse returns and {} working points of objects on the ground removed",
                  tree.sparse_removed, working.object_points_removed);
  }
  if (working.points.size() < 10) {
    throw InputError(source, "",
                     fmt::format("only {} points above the ground: no tree to reconstruct",
                                 working.points.size()));
  }
  return working;
}

// The base of the tree: the lowest band of the largest connected piece of the scan.
struct TreeBase {
  std::vector<int> roots;  // working points in that band
  double z = 0.0;          // height of the piece's lowest point
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double spread_m = 0.0;  // RMS horizontal distance of the roots from their centroid
};

// Connected pieces of the graph with its gap bridges: a tall tree whose upper trunk the scan
// saw sparsely falls into pieces, the crown the largest, which the bridges join again.
std::vector<int> BridgedPieces(const ScanGraph& graph) {
  std::vector<int> label(graph.size(), -1);
  std::vector<int> stack;
  int next = 0;
  for (int start = 0; start < graph.size(); ++start) {
    if (label[start] >= 0) continue;
    label[start] = next;
    stack.assign(1, start);
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      for (int k = graph.offsets[i]; k < graph.offsets[i + 1]; ++k) {
        const int j = graph.targets[k];
        if (label[j] < 0) {
          label[j] = next;
          stack.push_back(j);
        }
      }
    }
    ++next;
  }
  return label;
}

TreeBase FindBase(std::span<const Eigen::Vector3d> points, const ScanGraph& graph,
                  double band_width_m) {
  const std::vector<int> piece = BridgedPieces(graph);
  std::vector<int> piece_size(points.size(), 0);
  for (const int p : piece) ++piece_size[p];
  const int main_piece =
      static_cast<int>(std::max_element(piece_size.begin(), piece_size.end()) - piece_size.begin());
  TreeBase base;
  base.z = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < points.size(); ++i) {
    if (piece[i] == main_piece) base.z = std::min(base.z, points[i].z());
  }
  for (size_t i = 0; i < points.size(); ++i) {
    if (piece[i] == main_piece && points[i].z() <= base.z + band_width_m) {
      base.roots.push_back(static_cast<int>(i));
      base.centroid += points[i];
    }
  }
  base.centroid /= base.roots.size();
  for (const int r : base.roots) {
    base.spread_m += (points[r] - base.centroid).head<2>().squaredNorm();
  }
  base.spread_m = std::sqrt(base.spread_m / base.roots.size());
  return base;
}

// Distances along the scan from the base: they keep the trunk, the samples and the growth on the
// tree's own wood.
struct ScanGeodesics {
  ScanGraph graph;
  TreeBase base;
  GeodesicField field;
  double height_m = 0.0;  // of the highest point reached above the base
};

ScanGeodesics MeasureGeodesics(const WorkingCloud& working, const PointIndex& index) {
  ScanGeodesics out;
  out.graph = BuildScanGraph(working.points, index,
                             {.neighbour_radius_m = working.scale.neighbour_radius_m,
                              .max_gap_m = working.scale.max_gap_m});
  out.base = FindBase(working.points, out.graph, working.scale.band_width_m);
  out.field = GeodesicDistances(out.graph, out.base.roots);
  double z_top = out.base.z;
  for (size_t i = 0; i < working.points.size(); ++i) {
    if (std::isfinite(out.field.distance[i])) z_top = std::max(z_top, working.points[i].z());
  }
  out.height_m = z_top - out.base.z;
  spdlog::debug(
      "graph: {} points, {} pieces, {} bridges (longest {:.3f} m), {} base points, "
      "height {:.2f} m",
      working.points.size(), out.graph.pieces, out.graph.bridges, out.graph.longest_bridge_m,
      out.base.roots.size(), out.height_m);
  return out;
}

// The working points of the lowest `length` of the trunk (also within 1.5 lengths of the base
// along the scan), and which working points they are.
struct TrunkCandidates {
  std::vector<Eigen::Vector3d> points;
  std::vector<char> chosen;  // per working point
};

TrunkCandidates SelectTrunkStretch(std::span<const Eigen::Vector3d> working,
                                   const ScanGeodesics& geodesics, double length) {
  TrunkCandidates out;
  out.chosen.assign(working.size(), 0);
  for (size_t i = 0; i < working.size(); ++i) {
    if (geodesics.field.distance[i] <= 1.5 * length &&
        working[i].z() <= geodesics.base.z + length) {
      out.points.push_back(working[i]);
      out.chosen[i] = 1;
    }
  }
  return out;
}

// A tree that forks below the top of the stretch (a multi-stemmed tree forking at half a metre)
// gives MSAC stems to pass a cylinder through: the fit then holds for less than half the stretch
// (a stem's cylinder, shortened where it leaves the trunk), or not even at its lowest slice, so
// it cannot shorten itself onto the trunk.
bool MissesTheTrunk(const TrunkFit& fit, double stretch) {
  return fit.found &&
         ((!fit.slices.empty() && !fit.slices.front().agrees) || fit.length_m < 0.5 * stretch);
}

struct ShorterStretch {
  TrunkFit fit;
  TrunkCandidates candidates;
  double length_m = 0.0;
};

// Stretches halved down to trunk_fit_min_m, the first one the fit holds over; nothing when none
// does.
std::optional<ShorterStretch> FitBelowAFork(const WorkingCloud& working,
                                            const ScanGeodesics& geodesics, double full_length,
                                            const ReconstructionOptions& options) {
  double length = full_length;
  while (length > options.trunk_fit_min_m + 1e-9) {
    length = std::max(0.5 * length, options.trunk_fit_min_m);
    TrunkCandidates candidates = SelectTrunkStretch(working.points, geodesics, length);
    TrunkFit shorter =
        FitTrunkCylinder(candidates.points, geodesics.base.z, working.scale.trunk_threshold_m,
                         options.trunk, options.seed);
    spdlog::debug("trunk on the lowest {:.2f} m: found {}, radius {:.4f}, length {:.2f}; {}",
                  length, shorter.found, shorter.cylinder.radius, shorter.length_m, shorter.note);
    if (shorter.found && !MissesTheTrunk(shorter, length)) {
      return ShorterStretch{std::move(shorter), std::move(candidates), length};
    }
  }
  return std::nullopt;
}

struct CloudRefit {
  TrunkFit fit;
  size_t points = 0;
};

// A trunk only a few voxels in radius is measured again on the tree's own points in the chosen
// voxels (the working point nearest to them is that voxel's mean): averaging voxels about as
// wide as the depth noise across a thin trunk's blurred ring widens the ring. Nothing when no
// more points than the voxel means are found or the fit fails.
std::optional<CloudRefit> RefitOnCloudPoints(std::span<const Eigen::Vector3d> tree_points,
                                             const PointIndex& index,
                                             const TrunkCandidates& candidates,
                                             const ScanGeodesics& geodesics, double stretch_m,
                                             const WorkingCloud& working,
                                             const ReconstructionOptions& options) {
  const double voxel = working.scale.voxel_m;
  std::vector<Eigen::Vector3d> full;
  std::vector<int> near;
  std::vector<double> d2;
  for (const Eigen::Vector3d& p : tree_points) {
    if (p.z() > geodesics.base.z + stretch_m + voxel) continue;
    index.Nearest(p, 1, near, d2);
    if (!near.empty() && candidates.chosen[near[0]] && d2[0] <= voxel * voxel) full.push_back(p);
  }
  if (full.size() <= candidates.points.size()) return std::nullopt;
  TrunkFit refit = FitTrunkCylinder(full, geodesics.base.z, working.scale.trunk_threshold_m,
                                    options.trunk, options.seed);
  if (!refit.found) return std::nullopt;
  return CloudRefit{std::move(refit), full.size()};
}

// The trunk cylinder and the stretch of the trunk it was fitted on.
struct TrunkStep {
  TrunkFit fit;
  TrunkStretch stretch = TrunkStretch::kLowest;
  double stretch_m = 0.0;
};

// The MSAC cylinder is kept only when the slices across the trunk vouch for it; otherwise the
// slices' own cylinder replaces it, and without that the trunk has no cylinder (the base's spread
// sizes it).
void CheckAgainstSlices(TrunkStep& step, const TrunkCandidates& candidates, double base_z,
                        double band_m, const ReconstructionOptions& options) {
  if (!options.check_trunk_on_slices) return;
  TrunkFit slices =
      FitTrunkFromSlices(candidates.points, base_z, step.stretch_m, band_m, options.trunk_slices);
  for (const TrunkSlice& sl : slices.slices) {
    spdlog::debug("trunk slice {:.2f}-{:.2f} m: {} points, radius {:.4f}{}", sl.from_m, sl.to_m,
                  sl.points, sl.radius_m, sl.agrees ? ", agrees" : "");
  }
  std::string why;
  if (TrustTrunkCylinder(step.fit, slices, step.stretch_m, options.trunk_slices, &why)) return;
  spdlog::debug("trunk: MSAC cylinder not trusted ({}); slices: found {}, radius {:.4f}; {}", why,
                slices.found, slices.cylinder.radius, slices.note);
  if (slices.found) {
    slices.note = why + "; " + slices.note;
    step.fit = std::move(slices);
  } else {
    step.fit.found = false;
    step.fit.note = why + "; " + slices.note;
  }
}

// The paper's MSAC cylinder on the lowest stretch of the trunk; below a fork when the tree forks
// within it, on the cloud's own points when the trunk is only a few voxels wide.
TrunkStep FitTrunk(const WorkingCloud& working, const PointIndex& index,
                   const ScanGeodesics& geodesics, std::span<const Eigen::Vector3d> tree_points,
                   const ReconstructionOptions& options) {
  const double full_length = std::clamp(options.trunk_fit_share * geodesics.height_m,
                                        options.trunk_fit_min_m, options.trunk_fit_max_m);
  TrunkStep step;
  step.stretch_m = full_length;
  TrunkCandidates candidates = SelectTrunkStretch(working.points, geodesics, full_length);
  step.fit = FitTrunkCylinder(candidates.points, geodesics.base.z, working.scale.trunk_threshold_m,
                              options.trunk, options.seed);
  if (MissesTheTrunk(step.fit, full_length)) {
    if (std::optional<ShorterStretch> shorter =
            FitBelowAFork(working, geodesics, full_length, options)) {
      step.fit = std::move(shorter->fit);
      candidates = std::move(shorter->candidates);
      step.stretch = TrunkStretch::kBelowFork;
      step.stretch_m = shorter->length_m;
    }
  }
  size_t fitted_points = candidates.points.size();
  if (options.trunk_on_full_cloud && step.fit.found &&
      step.fit.cylinder.radius < options.trunk_voxels_for_full_cloud * working.scale.voxel_m) {
    if (std::optional<CloudRefit> refit = RefitOnCloudPoints(
            tree_points, index, candidates, geodesics, step.stretch_m, working, options)) {
      step.fit = std::move(refit->fit);
      fitted_points = refit->points;
    }
  }
  CheckAgainstSlices(step, candidates, geodesics.base.z, working.scale.trunk_threshold_m, options);
  if (step.stretch == TrunkStretch::kBelowFork) {
    const std::string shortened = fmt::format(
        "fitted on the lowest {:.2f} m (a fork below {:.2f} m)", step.stretch_m, full_length);
    step.fit.note = step.fit.note.empty() ? shortened : shortened + "; " + step.fit.note;
  }
  const TrunkFit& fit = step.fit;
  spdlog::debug(
      "trunk: {} candidate points, found {}, radius {:.4f} axis ({:.2f} {:.2f} {:.2f}) "
      "length {:.2f} inliers {} ({:.0f}%) rms {:.4f}; {}",
      fitted_points, fit.found, fit.cylinder.radius, fit.cylinder.axis.x(), fit.cylinder.axis.y(),
      fit.cylinder.axis.z(), fit.length_m, fit.inliers, 100 * fit.inlier_share, fit.rms_m,
      fit.note);
  return step;
}

// What the trunk fit leaves to warn about: no cylinder, or one its slices disagree with.
std::optional<std::string> TrunkWarning(const TrunkFit& trunk) {
  if (!trunk.found) {
    return fmt::format("no trunk cylinder: {}; the base radius is estimated from the lowest points",
                       trunk.note);
  }
  if (!trunk.slices_agree) {
    return fmt::format("trunk cylinder (radius {:.3f} m): slices along the axis disagree ({})",
                       trunk.cylinder.radius, trunk.note);
  }
  return std::nullopt;
}

struct Attraction {
  std::vector<AttractionPoint> points;
  size_t unreached_points = 0;  // working points no path or bridge reached from the base
};

// What colonization grows through: the medial samples of geodesic bands (on the axis whatever the
// wood's thickness), or the reached working points themselves.
Attraction ChooseAttractionPoints(const WorkingCloud& working, const ScanGeodesics& geodesics,
                                  const ReconstructionOptions& options) {
  Attraction out;
  if (options.medial_samples) {
    const GeodesicSampling sampling = SampleGeodesicBands(
        working.points, geodesics.graph, geodesics.field,
        {.band_width_m = working.scale.band_width_m, .merge_per_spread = options.merge_per_spread});
    out.unreached_points = sampling.unreached_points;
    out.points.reserve(sampling.samples.size());
    for (const GeodesicSample& s : sampling.samples) {
      out.points.push_back({s.position, static_cast<double>(s.points), s.spread_m, s.geodesic_m});
    }
    return out;
  }
  for (size_t i = 0; i < working.points.size(); ++i) {
    if (std::isfinite(geodesics.field.distance[i])) {
      out.points.push_back({working.points[i], 1.0, 0.0, geodesics.field.distance[i]});
    } else {
      ++out.unreached_points;
    }
  }
  return out;
}

// A warning when more than a tenth of the working points are left out of the model.
std::optional<std::string> UnreachedWarning(const Attraction& attraction,
                                            const WorkingCloud& working) {
  if (attraction.unreached_points <= working.points.size() / 10) return std::nullopt;
  return fmt::format(
      "{:.0f}% of the points are not connected to the base (gaps wider than {:.2f} m): they are "
      "left out of the model",
      100.0 * attraction.unreached_points / working.points.size(), working.scale.max_gap_m);
}

struct Growth {
  Skeleton skeleton;
  ColonizationStats stats;
};

// Space colonization from the trunk cylinder's base along its axis (from the base's lowest
// points, straight up, without a cylinder), at the lengths of the scale. Throws InputError naming
// `source` when nothing grows.
Growth Colonize(std::span<const AttractionPoint> attraction, const TrunkFit& trunk,
                const TreeBase& base, const ReconstructionScale& scale, const std::string& source,
                const ReconstructionOptions& options) {
  const ColonizationLengths lengths{.step_m = scale.step_m,
                                    .influence_radius_m = scale.influence_radius_m,
                                    .kill_radius_m = scale.kill_radius_m,
                                    .geodesic_slack_m = 3.0 * scale.band_width_m,
                                    .bridge_gap_m = scale.max_gap_m};
  const Eigen::Vector3d root =
      trunk.found ? trunk.base : Eigen::Vector3d(base.centroid.x(), base.centroid.y(), base.z);
  const Eigen::Vector3d up = trunk.found ? trunk.cylinder.axis : Eigen::Vector3d::UnitZ();
  Growth growth;
  growth.skeleton =
      GrowByColonization(attraction, root, up, lengths, options.colonization, &growth.stats);
  spdlog::debug(
      "colonization: {} nodes, {} iterations, {} bridges; weight reached {:.0f}, stuck "
      "{:.0f}, unreached {:.0f}",
      growth.skeleton.size(), growth.stats.iterations, growth.stats.bridges,
      growth.stats.reached_weight, growth.stats.stuck_weight, growth.stats.unreached_weight);
  if (growth.skeleton.size() < 2) {
    throw InputError(source, "",
                     "no tree grew from the base: nothing above the lowest points is connected "
                     "to them (expected a standing tree with Z up)");
  }
  return growth;
}

struct Pruned {
  Skeleton skeleton;
  TwigPruningStats stats;
};

// Twigs the scan does not support go. Unless set, twigs must be at least a quarter as dense as
// typical wood: the median attraction point stands for that many points per band width.
Pruned PruneUnsupportedTwigs(Skeleton grown, std::span<const AttractionPoint> attraction,
                             double band_width_m, const ReconstructionOptions& options) {
  Pruned out;
  if (!options.prune) {
    out.skeleton = std::move(grown);
    return out;
  }
  TwigPruningOptions pruning = options.pruning;
  if (pruning.min_support_per_m <= 0.0 && !attraction.empty()) {
    std::vector<double> weights;
    for (const AttractionPoint& a : attraction) weights.push_back(a.weight);
    std::nth_element(weights.begin(), weights.begin() + weights.size() / 2, weights.end());
    pruning.min_support_per_m = 0.25 * weights[weights.size() / 2] / band_width_m;
  }
  out.skeleton = PruneTwigs(grown, pruning, &out.stats);
  return out;
}

struct RadiusAnchor {
  std::vector<int> trunk_path;  // the heaviest path from the root: the trunk
  int node = 0;
  double radius_m = 0.0;  // 0 without a trunk cylinder
};

// The radii are anchored on the trunk cylinder at the middle of its stretch, on the trunk.
RadiusAnchor AnchorOnTrunk(const Skeleton& skeleton, const TrunkFit& trunk, bool anchor_on_slices) {
  RadiusAnchor anchor;
  anchor.trunk_path = HeaviestPath(skeleton);
  if (!trunk.found) return anchor;
  double best = std::numeric_limits<double>::infinity();
  for (const int i : anchor.trunk_path) {
    const double t = (skeleton.nodes[i].position - trunk.base).dot(trunk.cylinder.axis);
    if (std::abs(t - 0.5 * trunk.length_m) < best) {
      best = std::abs(t - 0.5 * trunk.length_m);
      anchor.node = i;
    }
  }
  anchor.radius_m = anchor_on_slices ? trunk.slice_radius_m : trunk.cylinder.radius;
  return anchor;
}

// The fitted stretch of the trunk goes (back) onto the cylinder's axis, the better measurement.
void SnapTrunkToCylinder(Skeleton& skeleton, std::span<const int> trunk_path,
                         const TrunkFit& trunk) {
  const Cylinder& c = trunk.cylinder;
  for (const int i : trunk_path) {
    SkeletonNode& node = skeleton.nodes[i];
    const double t = (node.position - trunk.base).dot(c.axis);
    // Within the stretch the slices vouch for (no fork in it) the heaviest path is the trunk.
    if (t >= 0 && t <= trunk.length_m && c.AxisDistance(node.position) < 1.5 * c.radius) {
      node.position = trunk.base + t * c.axis;
    }
  }
}

struct Radii {
  Skeleton skeleton;
  RadiusStats stats;
  TwigPruningStats inside_wood;  // twigs removed for running inside other wood
};

// Allometric radii anchored on the trunk and refined by local fits on the reached working points
// (which also recentre the nodes they measure); then twigs that run inside other wood go and the
// trunk is snapped onto its cylinder.
Radii MeasureRadii(Skeleton skeleton, const TrunkFit& trunk, const WorkingCloud& working,
                   const ScanGeodesics& geodesics, double roughness_m,
                   const ReconstructionOptions& options) {
  const RadiusAnchor anchor = AnchorOnTrunk(skeleton, trunk, options.anchor_on_slices);
  std::vector<Eigen::Vector3d> reached;
  reached.reserve(working.points.size());
  for (size_t i = 0; i < working.points.size(); ++i) {
    if (std::isfinite(geodesics.field.distance[i])) reached.push_back(working.points[i]);
  }
  Radii out;
  AssignRadii(skeleton, anchor.node, anchor.radius_m, std::max(geodesics.base.spread_m, 0.01),
              reached, roughness_m, options.radii, &out.stats);
  std::vector<int> trunk_path = anchor.trunk_path;
  if (options.prune) {
    skeleton = PruneTwigsInsideWood(skeleton, 0.6, 3, &out.inside_wood);
    trunk_path = HeaviestPath(skeleton);  // node ids changed
  }
  if (options.snap_trunk_to_cylinder && trunk.found) {
    SnapTrunkToCylinder(skeleton, trunk_path, trunk);
  }
  out.skeleton = std::move(skeleton);
  return out;
}

void LogTimes(const StageTimes& t) {
  spdlog::debug(
      "times: prepare {:.3f} scale {:.3f} graph {:.3f} trunk {:.3f} samples {:.3f} "
      "colonize {:.3f} refine {:.3f} radii {:.3f} branches {:.3f} total {:.3f} s",
      t.prepare_s, t.scale_s, t.graph_s, t.trunk_s, t.samples_s, t.colonize_s, t.refine_s,
      t.radii_s, t.branches_s, t.total_s);
}

}  // namespace

void ReconstructionScale::Validate() const {
  CheckNonNegative("voxel_m", voxel_m);
  CheckNonNegative("neighbour_radius_m", neighbour_radius_m);
  CheckNonNegative("band_width_m", band_width_m);
  CheckNonNegative("step_m", step_m);
  CheckNonNegative("influence_radius_m", influence_radius_m);
  CheckNonNegative("kill_radius_m", kill_radius_m);
  CheckNonNegative("max_gap_m", max_gap_m);
  CheckNonNegative("trunk_threshold_m", trunk_threshold_m);
}

void ReconstructionOptions::Validate() const {
  CheckNested("preparation", preparation);
  CheckNested("scale", scale);
  CheckAtLeast("max_working_points", max_working_points, 1);
  CheckNested("ground", ground);
  CheckNested("trunk", trunk);
  CheckShare("trunk_fit_share", trunk_fit_share);
  CheckPositive("trunk_fit_min_m", trunk_fit_min_m);
  CheckOrdered("trunk_fit_min_m", trunk_fit_min_m, "trunk_fit_max_m", trunk_fit_max_m);
  CheckPositive("band_per_link", band_per_link);
  CheckNonNegative("merge_per_spread", merge_per_spread);
  CheckNested("colonization", colonization);
  CheckNested("pruning", pruning);
  CheckNested("smoothing", smoothing);
  CheckNonNegative("trunk_voxels_for_full_cloud", trunk_voxels_for_full_cloud);
  CheckNested("trunk_slices", trunk_slices);
  CheckNested("radii", radii);
  CheckNested("branches", branches);
}

std::string ToString(TrunkStretch stretch) {
  switch (stretch) {
    case TrunkStretch::kLowest:
      return "lowest";
    case TrunkStretch::kBelowFork:
      return "below a fork";
  }
  return "unknown";
}

ReconstructionScale DeriveScale(const CloudScale& measured, const ReconstructionScale& given,
                                double band_per_link) {
  ReconstructionScale s = given;
  const double spacing = std::max(measured.spacing_m, 1e-4);
  const double roughness = measured.roughness_m;
  if (s.voxel_m <= 0) s.voxel_m = std::max(spacing, 0.002);
  const double effective = std::max(spacing, s.voxel_m);
  // Links must span a neighbourhood of the sparsest view, not the merged cloud's nearest pairs.
  const double neighbourhood = std::max(measured.neighbourhood_m, 2.0 * spacing);
  if (s.neighbour_radius_m <= 0) {
    s.neighbour_radius_m = std::max({1.5 * neighbourhood, 2.0 * effective, 4.0 * roughness});
  }
  // Bands half a link wide (band_per_link): a link spans at least three spacings, so a band still
  // holds a connected ring, and a twig leaving its parent gets its own band pieces (and samples)
  // within a link of the fork; the step and the kill distance follow, so a twig's samples are not
  // reached from the parent. The finest band resolves branches of ~1 cm radius.
  if (s.band_width_m <= 0) s.band_width_m = std::max(band_per_link * s.neighbour_radius_m, 0.015);
  if (s.step_m <= 0) s.step_m = s.band_width_m;
  if (s.influence_radius_m <= 0) s.influence_radius_m = 4.0 * s.band_width_m;
  if (s.kill_radius_m <= 0) s.kill_radius_m = 1.5 * s.band_width_m;
  if (s.max_gap_m <= 0) s.max_gap_m = std::max(0.3, 15.0 * effective);
  if (s.trunk_threshold_m <= 0) s.trunk_threshold_m = std::max({2.5 * roughness, effective, 0.005});
  return s;
}

ReconstructionResult ReconstructTree(std::span<const Eigen::Vector3d> points,
                                     const std::string& source,
                                     const ReconstructionOptions& options) {
  options.Validate();
  ReconstructionResult result;
  auto warn = [&](std::optional<std::string> message) {
    if (!message) return;
    spdlog::warn("{}: {}", source, *message);
    result.warnings.push_back(std::move(*message));
  };
  Stopwatch total, lap;
  PreparedCloud prepared = PrepareCloud(points, source, options.preparation);
  result.input_points = prepared.input_points;
  result.warnings = prepared.warnings;
  result.times.prepare_s = lap.Lap();

  const TreePoints tree = SeparateFromGround(std::move(prepared.points), options);
  const WorkingCloud working = MakeWorkingCloud(tree, source, options);
  result.ground = tree.ground;
  result.measured = tree.measured;
  result.scene_sparse_removed = tree.sparse_removed;
  result.parameters = working.scale;
  result.scene_object_points_removed = working.object_points_removed;
  result.working_points = working.points.size();
  result.times.scale_s = lap.Lap();

  const PointIndex index(working.points);
  const ScanGeodesics geodesics = MeasureGeodesics(working, index);
  result.graph_pieces = geodesics.graph.pieces;
  result.graph_bridges = geodesics.graph.bridges;
  result.times.graph_s = lap.Lap();

  TrunkStep trunk = FitTrunk(working, index, geodesics, tree.points, options);
  warn(TrunkWarning(trunk.fit));
  result.trunk = std::move(trunk.fit);
  result.trunk_stretch = trunk.stretch;
  result.trunk_stretch_m = trunk.stretch_m;
  result.times.trunk_s = lap.Lap();

  Attraction attraction = ChooseAttractionPoints(working, geodesics, options);
  warn(UnreachedWarning(attraction, working));
  result.unreached_points = attraction.unreached_points;
  result.attraction_points = attraction.points.size();
  result.times.samples_s = lap.Lap();

  Growth growth =
      Colonize(attraction.points, result.trunk, geodesics.base, working.scale, source, options);
  result.colonization = growth.stats;
  result.grown = growth.skeleton;
  result.times.colonize_s = lap.Lap();

  Pruned pruned = PruneUnsupportedTwigs(std::move(growth.skeleton), attraction.points,
                                        working.scale.band_width_m, options);
  SmoothSkeleton(pruned.skeleton, options.smoothing);
  result.times.refine_s = lap.Lap();

  Radii radii = MeasureRadii(std::move(pruned.skeleton), result.trunk, working, geodesics,
                             result.measured.roughness_m, options);
  result.radii = radii.stats;
  result.pruning = pruned.stats + radii.inside_wood;
  result.times.radii_s = lap.Lap();

  result.tree =
      DecomposeIntoBranches(radii.skeleton, options.branches, "reconstructed from " + source);
  Validate(result.tree, source);
  result.skeleton = std::move(radii.skeleton);
  result.attraction = std::move(attraction.points);
  result.times.branches_s = lap.Lap();
  result.times.total_s = total.Lap();
  LogTimes(result.times);
  return result;
}

}  // namespace simtree::reconstruction
