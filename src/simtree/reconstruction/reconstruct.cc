#include "simtree/reconstruction/reconstruct.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

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

}  // namespace

ReconstructionScale DeriveScale(const CloudScale& measured, const ReconstructionScale& given) {
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
  // Bands a little narrower than a link (finer samples along a branch), but wide enough that a
  // band holds a connected ring of points; the finest band resolves branches of ~1 cm radius.
  if (s.band_width_m <= 0) s.band_width_m = std::max(0.75 * s.neighbour_radius_m, 0.015);
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
  ReconstructionResult result;
  Stopwatch total, lap;
  const PreparedCloud prepared = PrepareCloud(points, source, options.preparation);
  result.input_points = prepared.input_points;
  result.warnings = prepared.warnings;
  auto warn = [&](std::string message) {
    spdlog::warn("{}: {}", source, message);
    result.warnings.push_back(std::move(message));
  };
  result.times.prepare_s = lap.Lap();

  // Scale: measured on the input. A scene cloud (a merged Kinect capture) is mostly ground: the
  // ground goes first, on every point, so that it decides neither the spacing nor the working
  // voxels, and the scale is measured again on what stands on it.
  result.measured = MeasureCloudScale(prepared.points, {.seed = options.seed});
  ReconstructionScale scale = DeriveScale(result.measured, options.scale);
  std::vector<Eigen::Vector3d> above_ground;
  std::span<const Eigen::Vector3d> tree_points = prepared.points;
  if (options.remove_ground) {
    GroundOptions ground_options = options.ground;
    ground_options.tolerance_m = std::max(ground_options.tolerance_m, scale.trunk_threshold_m);
    ground_options.seed = options.seed;
    result.ground = FindGroundPlane(prepared.points, ground_options);
    spdlog::debug(
        "ground: {} ({} points up to {:.3f} m, plane {:.2f} m wide, {:.2f} m standing on it, "
        "{:.0f}% covered)",
        result.ground.found ? "found" : "none", result.ground.ground_points,
        result.ground.clearance_m, result.ground.plane_width_m, result.ground.standing_width_m,
        100 * result.ground.covered_share);
    if (result.ground.found) {
      above_ground.reserve(prepared.points.size() - result.ground.ground_points);
      for (size_t i = 0; i < prepared.points.size(); ++i) {
        if (!result.ground.is_ground[i]) above_ground.push_back(prepared.points[i]);
      }
      if (options.clean_scene) {
        // Sparse returns: fewer neighbours than a surface seen at the measured spacing has.
        SparseReturnOptions sparse_options;
        sparse_options.radius_m = std::max(4.0 * result.measured.spacing_m, 0.01);
        const std::vector<char> sparse = FindSparseReturns(above_ground, sparse_options);
        std::erase_if(above_ground, [&](const Eigen::Vector3d& p) {
          return sparse[&p - above_ground.data()] != 0;
        });
        result.scene_sparse_removed =
            static_cast<size_t>(std::count(sparse.begin(), sparse.end(), 1));
      }
      tree_points = above_ground;
      if (above_ground.size() >= 10) {
        result.measured = MeasureCloudScale(above_ground, {.seed = options.seed});
        scale = DeriveScale(result.measured, options.scale);
      }
    }
  }
  double voxel = scale.voxel_m;
  std::vector<Eigen::Vector3d> working =
      VoxelAverageAtMost(tree_points, options.max_working_points, &voxel);
  if (voxel > scale.voxel_m * 1.001) {
    ReconstructionScale given = options.scale;
    given.voxel_m = voxel;
    scale = DeriveScale(result.measured, given);
  }
  result.parameters = scale;
  spdlog::debug(
      "scale: spacing {:.4f} roughness {:.4f}; voxel {:.4f} neighbours {:.4f} band {:.4f} "
      "step {:.4f} influence {:.4f} kill {:.4f} gap {:.3f} trunk {:.4f}",
      result.measured.spacing_m, result.measured.roughness_m, scale.voxel_m,
      scale.neighbour_radius_m, scale.band_width_m, scale.step_m, scale.influence_radius_m,
      scale.kill_radius_m, scale.max_gap_m, scale.trunk_threshold_m);
  result.times.scale_s = lap.Lap();
  if (result.ground.found && options.clean_scene) {
    GroundObjectOptions object_options;
    object_options.neighbour_radius_m = scale.neighbour_radius_m;
    object_options.touch_height_m = scale.band_width_m;
    const std::vector<char> object = FindObjectsOnGround(working, result.ground, object_options);
    std::vector<Eigen::Vector3d> kept;
    kept.reserve(working.size());
    for (size_t i = 0; i < working.size(); ++i) {
      if (!object[i]) kept.push_back(working[i]);
    }
    result.scene_object_points_removed = working.size() - kept.size();
    working = std::move(kept);
    spdlog::debug("scene: {} sparse returns and {} working points of objects on the ground removed",
                  result.scene_sparse_removed, result.scene_object_points_removed);
  }
  result.working_points = working.size();
  if (working.size() < 10) {
    throw InputError(source, "",
                     fmt::format("only {} points above the ground: no tree to "
                                 "reconstruct",
                                 working.size()));
  }

  // Neighbour graph, the base, geodesic distances.
  const PointIndex index(working);
  ScanGraphOptions graph_options;
  graph_options.neighbour_radius_m = scale.neighbour_radius_m;
  graph_options.max_gap_m = scale.max_gap_m;
  const ScanGraph graph = BuildScanGraph(working, index, graph_options);
  result.graph_pieces = graph.pieces;
  result.graph_bridges = graph.bridges;
  std::vector<int> piece_size(working.size(), 0);
  for (const int p : graph.piece) ++piece_size[p];
  const int main_piece =
      static_cast<int>(std::max_element(piece_size.begin(), piece_size.end()) - piece_size.begin());
  double z_base = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < working.size(); ++i) {
    if (graph.piece[i] == main_piece) z_base = std::min(z_base, working[i].z());
  }
  std::vector<int> roots;
  Eigen::Vector3d base_centroid = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < working.size(); ++i) {
    if (graph.piece[i] == main_piece && working[i].z() <= z_base + scale.band_width_m) {
      roots.push_back(static_cast<int>(i));
      base_centroid += working[i];
    }
  }
  base_centroid /= roots.size();
  double base_spread = 0.0;
  for (const int r : roots) {
    base_spread += (working[r] - base_centroid).head<2>().squaredNorm();
  }
  base_spread = std::sqrt(base_spread / roots.size());
  const GeodesicField field = GeodesicDistances(graph, roots);
  double z_top = z_base;
  for (size_t i = 0; i < working.size(); ++i) {
    if (std::isfinite(field.distance[i])) z_top = std::max(z_top, working[i].z());
  }
  const double height = z_top - z_base;
  spdlog::debug(
      "graph: {} points, {} pieces, {} bridges (longest {:.3f} m), {} base points, "
      "height {:.2f} m",
      working.size(), graph.pieces, graph.bridges, graph.longest_bridge_m, roots.size(), height);
  result.times.graph_s = lap.Lap();

  // Trunk cylinder on the lowest stretch of the trunk.
  double fit_length = std::clamp(options.trunk_fit_share * height, options.trunk_fit_min_m,
                                 options.trunk_fit_max_m);
  std::vector<Eigen::Vector3d> trunk_points;
  std::vector<char> trunk_voxel(working.size(), 0);
  auto select_trunk_points = [&](double length) {
    trunk_points.clear();
    std::fill(trunk_voxel.begin(), trunk_voxel.end(), 0);
    for (size_t i = 0; i < working.size(); ++i) {
      if (field.distance[i] <= 1.5 * length && working[i].z() <= z_base + length) {
        trunk_points.push_back(working[i]);
        trunk_voxel[i] = 1;
      }
    }
  };
  select_trunk_points(fit_length);
  TrunkFitOptions trunk_options = options.trunk;
  trunk_options.inlier_threshold_m = scale.trunk_threshold_m;
  trunk_options.seed = options.seed;
  result.trunk = FitTrunkCylinder(trunk_points, z_base, trunk_options);
  // A tree that forks below the top of the stretch (a multi-stemmed tree forking at half a
  // metre) gives MSAC stems to pass a cylinder through: the fit then holds for less than half the
  // stretch (a stem's cylinder, shortened where it leaves the trunk), or not even at its lowest
  // slice, so it cannot shorten itself onto the trunk. Fit shorter stretches, halving, and keep
  // the first the fit holds over (synth magnolia forking at 0.6 m: a 1.01 m "trunk" and no tree
  // grown).
  auto misses_the_trunk = [](const TrunkFit& fit, double stretch) {
    return fit.found &&
           ((!fit.slices.empty() && !fit.slices.front().agrees) || fit.length_m < 0.5 * stretch);
  };
  std::string shortened;  // said in the trunk's note, which the refit below replaces
  double length = fit_length;
  while (misses_the_trunk(result.trunk, fit_length) && length > options.trunk_fit_min_m + 1e-9) {
    length = std::max(0.5 * length, options.trunk_fit_min_m);
    select_trunk_points(length);
    TrunkFit shorter = FitTrunkCylinder(trunk_points, z_base, trunk_options);
    spdlog::debug("trunk on the lowest {:.2f} m: found {}, radius {:.4f}, length {:.2f}; {}",
                  length, shorter.found, shorter.cylinder.radius, shorter.length_m, shorter.note);
    if (shorter.found && !misses_the_trunk(shorter, length)) {
      shortened =
          fmt::format("fitted on the lowest {:.2f} m (a fork below {:.2f} m)", length, fit_length);
      result.trunk = std::move(shorter);
      fit_length = length;
      break;
    }
  }
  // No shorter stretch held: the points are the full stretch's again.
  if (shortened.empty() && length != fit_length) select_trunk_points(fit_length);
  if (options.trunk_on_full_cloud && result.trunk.found &&
      result.trunk.cylinder.radius < options.trunk_voxels_for_full_cloud * voxel) {
    // A trunk only a few voxels in radius is measured again on the points themselves: the points
    // of every voxel chosen above (the working point nearest to them is that voxel's mean).
    // Averaging voxels about as wide as the depth noise across a thin trunk's blurred ring widens
    // the ring (synth: +5% on a 2.6 cm trunk in 9 mm voxels, +12% in 11 mm ones; -4% on both
    // from the points).
    std::vector<Eigen::Vector3d> full;
    std::vector<int> near;
    std::vector<double> d2;
    for (const Eigen::Vector3d& p : tree_points) {
      if (p.z() > z_base + fit_length + voxel) continue;
      index.Nearest(p, 1, near, d2);
      if (!near.empty() && trunk_voxel[near[0]] && d2[0] <= voxel * voxel) full.push_back(p);
    }
    if (full.size() > trunk_points.size()) {
      TrunkFit refit = FitTrunkCylinder(full, z_base, trunk_options);
      if (refit.found) {
        result.trunk = std::move(refit);
        trunk_points = std::move(full);
      }
    }
  }
  if (!shortened.empty()) {
    result.trunk.note =
        result.trunk.note.empty() ? shortened : shortened + "; " + result.trunk.note;
  }
  if (!result.trunk.found) {
    warn(fmt::format("no trunk cylinder: {}; the base radius is estimated from the lowest points",
                     result.trunk.note));
  } else if (!result.trunk.slices_agree) {
    warn(fmt::format("trunk cylinder (radius {:.3f} m): slices along the axis disagree ({})",
                     result.trunk.cylinder.radius, result.trunk.note));
  }
  spdlog::debug(
      "trunk: {} candidate points, found {}, radius {:.4f} axis ({:.2f} {:.2f} {:.2f}) "
      "length {:.2f} inliers {} ({:.0f}%) rms {:.4f}; {}",
      trunk_points.size(), result.trunk.found, result.trunk.cylinder.radius,
      result.trunk.cylinder.axis.x(), result.trunk.cylinder.axis.y(),
      result.trunk.cylinder.axis.z(), result.trunk.length_m, result.trunk.inliers,
      100 * result.trunk.inlier_share, result.trunk.rms_m, result.trunk.note);
  result.times.trunk_s = lap.Lap();

  // Attraction points.
  std::vector<AttractionPoint> attraction;
  if (options.medial_samples) {
    GeodesicSampleOptions sample_options;
    sample_options.band_width_m = scale.band_width_m;
    sample_options.merge_per_spread = options.merge_per_spread;
    const GeodesicSampling sampling = SampleGeodesicBands(working, graph, field, sample_options);
    result.unreached_points = sampling.unreached_points;
    attraction.reserve(sampling.samples.size());
    for (const GeodesicSample& s : sampling.samples) {
      attraction.push_back({s.position, static_cast<double>(s.points), s.spread_m, s.geodesic_m});
    }
  } else {
    for (size_t i = 0; i < working.size(); ++i) {
      if (std::isfinite(field.distance[i])) {
        attraction.push_back({working[i], 1.0, 0.0, field.distance[i]});
      } else {
        ++result.unreached_points;
      }
    }
  }
  result.attraction_points = attraction.size();
  if (result.unreached_points > working.size() / 10) {
    warn(
        fmt::format("{:.0f}% of the points are not connected to the base (gaps wider than "
                    "{:.2f} m): they are left out of the model",
                    100.0 * result.unreached_points / working.size(), scale.max_gap_m));
  }
  result.times.samples_s = lap.Lap();

  // Space colonization from the base of the trunk.
  ColonizationOptions colonization = options.colonization;
  colonization.step_m = scale.step_m;
  colonization.influence_radius_m = scale.influence_radius_m;
  colonization.kill_radius_m = scale.kill_radius_m;
  if (colonization.bridge_gap_m > 0) colonization.bridge_gap_m = scale.max_gap_m;
  if (colonization.geodesic_slack_m >= 0) colonization.geodesic_slack_m = 3.0 * scale.band_width_m;
  const Eigen::Vector3d root = result.trunk.found
                                   ? result.trunk.base
                                   : Eigen::Vector3d(base_centroid.x(), base_centroid.y(), z_base);
  const Eigen::Vector3d up =
      result.trunk.found ? result.trunk.cylinder.axis : Eigen::Vector3d::UnitZ();
  Skeleton skeleton = GrowByColonization(attraction, root, up, colonization, &result.colonization);
  if (skeleton.size() < 2) {
    throw InputError(source, "",
                     "no tree grew from the base: nothing above the lowest points is connected "
                     "to them (expected a standing tree with Z up)");
  }
  spdlog::debug(
      "colonization: {} nodes, {} iterations, {} bridges; weight reached {:.0f}, stuck "
      "{:.0f}, unreached {:.0f}",
      skeleton.size(), result.colonization.iterations, result.colonization.bridges,
      result.colonization.reached_weight, result.colonization.stuck_weight,
      result.colonization.unreached_weight);
  result.grown = skeleton;
  result.times.colonize_s = lap.Lap();

  if (options.prune) {
    // Twigs must be at least a quarter as dense as typical wood: the median attraction point
    // stands for that many points per band width.
    TwigPruningOptions pruning = options.pruning;
    if (pruning.min_support_per_m <= 0.0 && !attraction.empty()) {
      std::vector<double> weights;
      for (const AttractionPoint& a : attraction) weights.push_back(a.weight);
      std::nth_element(weights.begin(), weights.begin() + weights.size() / 2, weights.end());
      pruning.min_support_per_m = 0.25 * weights[weights.size() / 2] / scale.band_width_m;
    }
    skeleton = PruneTwigs(skeleton, pruning, &result.pruning);
  }
  SmoothSkeleton(skeleton, options.smoothing);
  // Radii, anchored on the trunk cylinder at the middle of its stretch (on the heaviest path
  // from the root: the trunk), refined by local fits that also recentre the nodes they measure.
  std::vector<int> trunk_path = HeaviestPath(skeleton);
  int anchor = 0;
  double anchor_radius = 0.0;
  if (result.trunk.found) {
    double best = std::numeric_limits<double>::infinity();
    for (const int i : trunk_path) {
      const double t =
          (skeleton.nodes[i].position - result.trunk.base).dot(result.trunk.cylinder.axis);
      if (std::abs(t - 0.5 * result.trunk.length_m) < best) {
        best = std::abs(t - 0.5 * result.trunk.length_m);
        anchor = i;
      }
    }
    anchor_radius =
        options.anchor_on_slices ? result.trunk.slice_radius_m : result.trunk.cylinder.radius;
  }
  result.times.refine_s = lap.Lap();
  std::vector<Eigen::Vector3d> reached;
  reached.reserve(working.size());
  for (size_t i = 0; i < working.size(); ++i) {
    if (std::isfinite(field.distance[i])) reached.push_back(working[i]);
  }
  AssignRadii(skeleton, anchor, anchor_radius, std::max(base_spread, 0.01), reached,
              result.measured.roughness_m, options.radii, &result.radii);
  if (options.prune) {
    TwigPruningStats inside;
    skeleton = PruneTwigsInsideWood(skeleton, 0.6, 3, &inside);
    result.pruning.twigs_removed += inside.twigs_removed;
    result.pruning.nodes_removed += inside.nodes_removed;
    trunk_path = HeaviestPath(skeleton);  // node ids changed
  }
  // The fitted stretch of the trunk goes (back) onto the cylinder's axis, the better measurement.
  if (options.snap_trunk_to_cylinder && result.trunk.found) {
    const Cylinder& c = result.trunk.cylinder;
    for (const int i : trunk_path) {
      SkeletonNode& node = skeleton.nodes[i];
      const double t = (node.position - result.trunk.base).dot(c.axis);
      // Within the stretch the slices vouch for (no fork in it) the heaviest path is the trunk.
      if (t >= 0 && t <= result.trunk.length_m && c.AxisDistance(node.position) < 1.5 * c.radius) {
        node.position = result.trunk.base + t * c.axis;
      }
    }
  }
  result.times.radii_s = lap.Lap();

  result.tree = DecomposeIntoBranches(skeleton, options.branches, "reconstructed from " + source);
  Validate(result.tree, source);
  result.skeleton = std::move(skeleton);
  result.attraction = std::move(attraction);
  result.times.branches_s = lap.Lap();
  result.times.total_s = total.Lap();
  const StageTimes& t = result.times;
  spdlog::debug(
      "times: prepare {:.3f} scale {:.3f} graph {:.3f} trunk {:.3f} samples {:.3f} "
      "colonize {:.3f} refine {:.3f} radii {:.3f} branches {:.3f} total {:.3f} s",
      t.prepare_s, t.scale_s, t.graph_s, t.trunk_s, t.samples_s, t.colonize_s, t.refine_s,
      t.radii_s, t.branches_s, t.total_s);
  return result;
}

}  // namespace simtree::reconstruction
