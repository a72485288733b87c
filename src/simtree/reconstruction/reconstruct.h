#pragma once
// Static tree reconstruction (paper Section III-B): from a registered point cloud to a complete
// simtree tree with a branch hierarchy and radii. ReconstructTree runs these steps in order
// (helpers in detail/):
//
//   prepare the cloud: NaN, duplicates, units, shape  -> cloud_preparation.h
//   measure its scale: spacing, roughness              -> cloud_scale.h
//   ground (when scanned) and the scene on it          -> ground_plane.h, scene_cleanup.h
//   working voxels                                     -> voxel_grid.h
//   scan graph: neighbours, gap bridges, geodesics     -> scan_graph.h
//   trunk cylinder by MSAC + slice check               -> trunk_cylinder.h
//   the cylinder trusted or replaced by slice circles  -> trunk_from_slices.h
//   medial samples along geodesic bands                -> geodesic_samples.h
//   improved space colonization                        -> space_colonization.h
//   twig pruning, smoothing                            -> twig_pruning.h, skeleton_smoothing.h
//   allometric radii with local fits                   -> allometric_radii.h
//   branch decomposition                               -> branch_decomposition.h
//
// Every length the steps use is derived from the measured point spacing and roughness unless it
// is set in ReconstructionOptions::scale (0 means "derive it"); ReconstructionResult::parameters
// reports the values used. docs/reconstruction.md explains each choice.
//
// Usage:
//   const std::vector<Eigen::Vector3d> points = ...;  // the merged cloud, metres, Z up
//   const simtree::reconstruction::ReconstructionResult result =
//       simtree::reconstruction::ReconstructTree(points, "merged.ply", {});
//   simtree::WriteTreeJson(result.tree, "static.json");

#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "simtree/core/option_checks.h"
#include "simtree/core/tree.h"
#include "simtree/reconstruction/detail/allometric_radii.h"
#include "simtree/reconstruction/detail/branch_decomposition.h"
#include "simtree/reconstruction/detail/cloud_preparation.h"
#include "simtree/reconstruction/detail/cloud_scale.h"
#include "simtree/reconstruction/detail/ground_plane.h"
#include "simtree/reconstruction/detail/scene_cleanup.h"
#include "simtree/reconstruction/detail/skeleton.h"
#include "simtree/reconstruction/detail/skeleton_smoothing.h"
#include "simtree/reconstruction/detail/space_colonization.h"
#include "simtree/reconstruction/detail/trunk_cylinder.h"
#include "simtree/reconstruction/detail/trunk_from_slices.h"
#include "simtree/reconstruction/detail/twig_pruning.h"

namespace simtree::reconstruction {

// The lengths the steps run at (metres). In ReconstructionOptions, 0 means: derive from the cloud.
struct ReconstructionScale {
  double voxel_m = 0.0;             // working resolution (points are averaged per voxel)
  double neighbour_radius_m = 0.0;  // neighbour graph links
  double band_width_m = 0.0;        // geodesic bands of the medial samples
  double step_m = 0.0;              // colonization step
  double influence_radius_m = 0.0;  // colonization perception
  double kill_radius_m = 0.0;       // colonization reach
  double max_gap_m = 0.0;           // occlusion gaps bridged (graph and colonization)
  double trunk_threshold_m = 0.0;   // MSAC inlier distance of the trunk cylinder

  // Throws OptionError for a negative or non-finite length.
  void Validate() const;
};

struct ReconstructionOptions {
  CloudPreparationOptions preparation;  // input checks, units
  ReconstructionScale scale;            // zeros: derived from the cloud (DeriveScale)
  int max_working_points = 60000;       // working points at most (a coarser voxel above)
  bool remove_ground = true;            // look for a ground plane and leave it out
  GroundOptions ground;  // the ground search; its tolerance is at least scale.trunk_threshold_m
  // With ground found (a scene, not a segmented tree): sparse returns and the objects standing
  // on the ground apart from the tree are removed (scene_cleanup.h).
  bool clean_scene = true;
  TrunkFitOptions trunk;          // the trunk cylinder (its MSAC band: scale.trunk_threshold_m)
  double trunk_fit_share = 0.25;  // share of the tree's height the trunk is fitted on...
  double trunk_fit_min_m = 0.3;   // ... in metres at least...
  double trunk_fit_max_m = 1.3;   // ... and at most
  // Attraction points: medial samples of geodesic bands (true) or the working points themselves.
  bool medial_samples = true;
  // Derived band width in neighbour links (when scale.band_width_m is 0); DeriveScale.
  double band_per_link = 0.5;
  // Arcs of one band merged into rings (geodesic_samples.h); 0 turns merging off.
  double merge_per_spread = 0.9;
  ColonizationOptions colonization;  // its lengths come from `scale`
  bool prune = true;                 // twig pruning, before and after the radii
  // min_support_per_m 0: a quarter of the median attraction point's weight per band width.
  TwigPruningOptions pruning;
  SkeletonSmoothingOptions smoothing;
  bool snap_trunk_to_cylinder = true;  // trunk nodes within the fitted stretch onto its axis
  // Anchor the radii on the median radius of the slice circles along the MSAC cylinder (true) or
  // on the cylinder's own radius (false, the paper's): on synth's thin, noisy trunks the slices
  // are the better measurement (docs/reconstruction.md).
  bool anchor_on_slices = true;
  // Fit the trunk again on the cloud's own points of the trunk stretch when the first fit's
  // radius is under trunk_voxels_for_full_cloud working voxels: voxels as wide as the depth noise
  // widen a thin trunk's blurred ring.
  bool trunk_on_full_cloud = true;
  // The final cylinder is checked against circles fitted slab by slab across the trunk
  // (trunk_from_slices.h) and replaced by theirs when they disagree or it holds too little.
  bool check_trunk_on_slices = true;
  SliceTrunkOptions trunk_slices;
  double trunk_voxels_for_full_cloud = 4.0;  // working voxels
  RadiusOptions radii;
  BranchDecompositionOptions branches;
  uint64_t seed = 1;  // of every random choice: scale sample, ground RANSAC, trunk MSAC

  // Throws OptionError naming the first field out of range ("trunk.slices").
  void Validate() const;
};

// Which stretch of the trunk its cylinder was fitted on.
enum class TrunkStretch {
  kLowest,     // the lowest trunk_fit_share of the tree (within [trunk_fit_min_m, max])
  kBelowFork,  // a shorter one: the tree forks within the lowest stretch
};
std::string ToString(TrunkStretch stretch);

// Wall-clock seconds per step.
struct StageTimes {
  double prepare_s = 0, scale_s = 0, graph_s = 0, trunk_s = 0, samples_s = 0, colonize_s = 0,
         refine_s = 0, radii_s = 0, branches_s = 0, total_s = 0;
};

struct ReconstructionResult {
  Tree tree;
  Skeleton skeleton;  // the final skeleton the tree was decomposed from, with radii
  // What colonization grew from (for pictures and diagnosis) and its skeleton before pruning.
  std::vector<AttractionPoint> attraction;
  Skeleton grown;
  TrunkFit trunk;
  TrunkStretch trunk_stretch = TrunkStretch::kLowest;
  double trunk_stretch_m = 0.0;  // metres of the trunk the cylinder was fitted on
  GroundPlane ground;
  CloudScale measured;             // spacing and roughness of the tree's points
  ReconstructionScale parameters;  // the lengths actually used
  size_t input_points = 0, working_points = 0, attraction_points = 0;
  size_t scene_sparse_removed = 0, scene_object_points_removed = 0;  // clean_scene
  size_t unreached_points = 0;  // working points no path or bridge reached from the base
  int graph_pieces = 0, graph_bridges = 0;
  ColonizationStats colonization;
  TwigPruningStats pruning;
  RadiusStats radii;
  std::vector<std::string> warnings;
  StageTimes times;
};

// The lengths derived from a measured spacing and roughness (where `given` has zeros).
// `band_per_link`: the band width in neighbour links (ReconstructionOptions::band_per_link).
ReconstructionScale DeriveScale(const CloudScale& measured, const ReconstructionScale& given,
                                double band_per_link = 0.5);

// Throws OptionError for invalid options, InputError naming `source` for input that is not a
// tree cloud (cloud_preparation.h) and when no tree can be grown from the base.
ReconstructionResult ReconstructTree(std::span<const Eigen::Vector3d> points,
                                     const std::string& source,
                                     const ReconstructionOptions& options = {});

}  // namespace simtree::reconstruction
