#pragma once
// One view made ready for registration: its tree cloud with camera-oriented normals, its up
// direction, its trunk and key region, and the points coarse registration aligns (by default the
// L1-medial skeleton of the key region, the paper's choice) with their normals and FPFH features.
// A view is prepared once and takes part in many pairs.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <open3d/geometry/KDTreeFlann.h>
#include <open3d/geometry/PointCloud.h>
#include <open3d/pipelines/registration/Feature.h>
#include <Eigen/Core>

#include "simtree/preprocessing/preprocess.h"
#include "simtree/preprocessing/preprocess_view.h"
#include "simtree/registration/detail/l1_medial_skeleton.h"
#include "simtree/registration/detail/medial_projection.h"
#include "simtree/registration/detail/trunk.h"

namespace simtree::registration {

// What coarse registration aligns (paper Table I's four rows).
enum class CoarseInput {
  kEntireTree,         // every point of the view (downsampled)
  kKeyRegion,          // the points inside the key region
  kTreeSkeleton,       // the L1-medial skeleton of the whole view
  kKeyRegionSkeleton,  // the L1-medial skeleton of the key region (the paper's)
};
const char* ToString(CoarseInput input);
// Throws InputError for an unknown name.
CoarseInput ParseCoarseInput(const std::string& name);

struct RegistrationViewOptions {
  CoarseInput coarse_input = CoarseInput::kKeyRegionSkeleton;  // what coarse registration aligns
  double normal_radius_factor = 3.0;  // point spacings, > 0: the normals' neighbourhood radius
  int normal_max_neighbors = 30;      // >= 1: the normals' neighbours
  TrunkOptions trunk;                 // the trunk and its first fork (trunk.h)
  CylinderFitOptions cylinder;        // the trunk's cylinder
  KeyRegionOptions key_region;        // the sphere around the fork
  // The L1-medial skeleton; its initial_radius_m is the least initial neighbourhood, raised to
  // skeleton_radius_factor point spacings.
  SkeletonOptions skeleton{.initial_radius_m = 0.04};
  // The skeleton is built from the view's points moved onto their branch axes (true) or from the
  // points themselves (false). The axis points are computed either way: the fine stage aligns
  // them (PairOptions::medial).
  bool medial_projection = true;
  // The projection onto the branch axes. Its neighbourhood_m is the least neighbourhood, raised to
  // projection_radius_factor point spacings; its max_shift_m holds for a view without a trunk
  // (with one: projection_shift_trunk_share of the trunk's visible width, at least
  // projection_min_shift_m). Branches narrower than the neighbourhood take their axis points
  // from their silhouettes (`silhouette`): the normal lines' meeting points sit towards the
  // camera on thin branches.
  MedialProjectionOptions projection{.silhouette = true};
  double projection_radius_factor = 4.0;      // point spacings, >= 0
  double projection_shift_trunk_share = 0.6;  // of the trunk's visible width, >= 0
  double projection_min_shift_m = 0.05;       // m, >= 0
  double skeleton_input_voxel_factor = 1.0;   // point spacings, > 0: axis points thinned to this
  double skeleton_radius_factor = 4.0;        // point spacings, >= 0: the skeleton's initial h
  double coarse_voxel_factor = 2.0;  // point spacings, > 0: point inputs downsampled to this
  // Coarse points' spacings, > 0: the radii of their normals and of their FPFH features.
  double feature_normal_factor = 3.0;
  double feature_radius_factor = 8.0;

  // Throws InputError naming the field of a nonsense value (trunk.slice_height_m, ...).
  void Validate() const;
};

struct RegistrationView {
  std::string name;
  // Camera frame, normals oriented to the camera. Shared and never changed once the view is
  // prepared: Open3D 0.16's KDTreeFlann (Debian build) indexes the cloud's own point buffer
  // without copying it, so the tree is only valid while this very cloud lives.
  std::shared_ptr<const open3d::geometry::PointCloud> cloud;
  std::shared_ptr<const open3d::geometry::KDTreeFlann> cloud_tree;
  // Per point: how plane-like its neighbourhood is, (l1 - l0) / l2 of the covariance's
  // eigenvalues l0 <= l1 <= l2. Near 0 on twigs (a line: the normal is any direction across it)
  // and on noise; fine registration trusts only plane-like points' normals.
  std::shared_ptr<const std::vector<float>> planarity;
  // The view's points moved onto their branch axes (medial_projection.h), one per point spacing:
  // two views of a branch agree on its axis though they see opposite halves of its surface.
  // Empty when the view cannot register.
  std::shared_ptr<const open3d::geometry::PointCloud> medial;
  std::shared_ptr<const open3d::geometry::KDTreeFlann> medial_tree;
  // Up in the camera frame: the ground's normal, else the trunk's axis, else the camera's -y.
  Eigen::Vector3d up = -Eigen::Vector3d::UnitY();
  std::optional<preprocessing::GroundPlane> ground;
  double spacing_m = 0.0;
  std::optional<TrunkFit> trunk;
  std::optional<KeyRegion> key_region;
  std::string failure;  // why this view cannot be coarsely registered (empty when it can)
  CoarseInput coarse_input = CoarseInput::kKeyRegionSkeleton;
  // The coarse points of the whole view (skeleton or downsampled surface) with normals; a pair
  // aligns those inside its key regions (SharedKeyRegions) or all of them.
  open3d::geometry::PointCloud coarse;
  std::shared_ptr<open3d::pipelines::registration::Feature> features;  // FPFH of `coarse`
  double coarse_spacing_m = 0.0;
  double seconds = 0.0;  // time to prepare

  bool CanRegister() const { return failure.empty(); }
};

bool UsesKeyRegion(CoarseInput input);

// The trunk's axis (of the cylinder when fitted), else up.
Eigen::Vector3d TrunkAxis(const RegistrationView& view);
// Height of a point in the view: above the ground when `use_ground` and the view has one, else
// along the trunk's axis above its base. Two views measure the same height at the same place.
double HeightOf(const RegistrationView& view, const Eigen::Vector3d& point, bool use_ground);
// The point of the trunk's axis at a height (HeightOf); nullopt without a trunk.
std::optional<Eigen::Vector3d> TrunkPointAtHeight(const RegistrationView& view, double height_m,
                                                  bool use_ground);

// Prepares a preprocessed view (PreprocessView's cloud, up and ground). Never throws for a view
// that merely lacks a trunk: `failure` says so and the view's pairs are flagged. Throws
// InputError for nonsense options.
RegistrationView PrepareView(const std::string& name,
                             const preprocessing::PreprocessResult& preprocessed,
                             const RegistrationViewOptions& options = {});

// Every view of a capture prepared (in parallel, with progress); a view that failed in
// preprocessing keeps its failure.
std::vector<RegistrationView> PrepareViews(
    const std::vector<preprocessing::PreprocessedView>& preprocessed,
    const RegistrationViewOptions& options = {});

}  // namespace simtree::registration
