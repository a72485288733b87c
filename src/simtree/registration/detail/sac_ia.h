#pragma once
// Sample Consensus Initial Alignment (Rusu et al. 2009), the coarse stage of the paper: draw a
// few source points, pair each with one of the target points whose FPFH is most similar, fit a
// rigid transform to the pairs, score it by the truncated distance of every transformed source
// point to the target, keep the best.
//
// Made robust here by two priors the paper does not use, both optional:
// - up: both views know their up direction (the ground's normal), so a hypothesis only chooses
//   a turn about up and a shift (the rotation aligns the ups exactly);
// - centre: both views know their key region's centre (the first branching point), so a
//   hypothesis that moves one far from the other is refused before it is scored.

#include <cstdint>
#include <optional>

#include <open3d/geometry/PointCloud.h>
#include <open3d/pipelines/registration/Feature.h>
#include <Eigen/Geometry>

namespace simtree::registration {

struct SacIaOptions {
  int iterations = 4000;      // hypotheses drawn, >= 1
  int samples = 3;            // sample points per hypothesis, >= 2 (2 only fix a pose with up)
  int feature_neighbors = 4;  // >= 1: each sample picks among this many most similar targets
  double min_sample_distance_m = 0.08;  // m, >= 0: sample points this far apart (a stable triangle)
  // [0, 1]: a sample whose matched edges' shorter length is below this share of the longer one
  // is refused unfitted.
  double edge_length_similarity = 0.8;
  double inlier_distance_m = 0.05;  // m, > 0: a source point this close is matched; errors cut here
  int refine_iterations = 15;       // >= 0: closest-point refinements of the best hypothesis
  uint64_t seed = 1;                // of the draws

  // Throws InputError naming the field of a nonsense value.
  void Validate() const;
};

// What both views know besides their points (all in each view's own frame).
struct SacIaPrior {
  std::optional<Eigen::Vector3d> source_up, target_up;
  std::optional<Eigen::Vector3d> source_center, target_center;
  double max_center_offset_m = 0.0;  // > 0: refuse hypotheses moving the centres further apart
};

struct CoarseAlignment {
  bool found = false;
  Eigen::Isometry3d target_from_source = Eigen::Isometry3d::Identity();
  double inlier_share = 0.0;  // source points within inlier_distance_m of the target
  double rmse_m = 0.0;        // of those inliers
  int hypotheses = 0;         // transforms scored
  double seconds = 0.0;
};

CoarseAlignment SampleConsensusInitialAlignment(
    const open3d::geometry::PointCloud& source,
    const open3d::pipelines::registration::Feature& source_features,
    const open3d::geometry::PointCloud& target,
    const open3d::pipelines::registration::Feature& target_features, const SacIaPrior& prior,
    const SacIaOptions& options = {});

// The rigid transform that best maps `from` onto `to` (least squares). With `up` given
// (from_up, to_up), the rotation maps from_up onto to_up exactly and only the turn about to_up is
// fitted.
Eigen::Isometry3d FitRigid(const std::vector<Eigen::Vector3d>& from,
                           const std::vector<Eigen::Vector3d>& to,
                           const std::optional<Eigen::Vector3d>& from_up = std::nullopt,
                           const std::optional<Eigen::Vector3d>& to_up = std::nullopt);

}  // namespace simtree::registration
