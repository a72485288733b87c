#include "simtree/registration/registration_view.h"

#include <chrono>

#include <Eigen/Eigenvalues>

#include <fmt/format.h>
#include <oneapi/tbb/parallel_for.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/progress.h"
#include "simtree/preprocessing/point_spacing.h"
#include "simtree/registration/detail/medial_projection.h"

namespace simtree::registration {
namespace {

using open3d::geometry::KDTreeSearchParamHybrid;
using open3d::geometry::PointCloud;

// Normals and FPFH of the coarse points; normals towards the camera for surfaces, along up for
// skeleton points (a skeleton has no outside: up is the one direction both views agree on).
void ComputeFeatures(RegistrationView& view, bool skeleton,
                     const RegistrationViewOptions& options) {
  view.coarse_spacing_m = preprocessing::MedianPointSpacing(view.coarse);
  const double s = std::max(view.coarse_spacing_m, 1e-3);
  view.coarse.EstimateNormals(KDTreeSearchParamHybrid(options.feature_normal_factor * s, 30));
  if (skeleton) {
    view.coarse.OrientNormalsToAlignWithDirection(view.up);
  } else {
    view.coarse.OrientNormalsTowardsCameraLocation(Eigen::Vector3d::Zero());
  }
  view.features = open3d::pipelines::registration::ComputeFPFHFeature(
      view.coarse, KDTreeSearchParamHybrid(options.feature_radius_factor * s, 100));
}

// The view's points moved onto their branch axes (medial_projection.h), thinned to one per
// `voxel_factor` point spacings (the projected points crowd onto the axes).
std::vector<Eigen::Vector3d> MedialPoints(const RegistrationView& view,
                                          const std::vector<size_t>& indices,
                                          const RegistrationViewOptions& options) {
  MedialProjectionOptions projection = options.projection;
  projection.neighbourhood_m =
      std::max(projection.neighbourhood_m, options.projection_radius_factor * view.spacing_m);
  if (view.trunk) {
    projection.max_shift_m =
        std::max(options.projection_min_shift_m,
                 options.projection_shift_trunk_share * view.trunk->visible_width_m);
  }
  PointCloud projected;
  projected.points_ = ProjectToMedialAxes(*view.cloud, *view.cloud_tree, indices, projection);
  return projected.VoxelDownSample(options.skeleton_input_voxel_factor * view.spacing_m)->points_;
}

// The L1-medial skeleton of `points` (medial points, or raw ones when not projected).
PointCloud SkeletonCloud(const RegistrationView& view, const std::vector<Eigen::Vector3d>& points,
                         const RegistrationViewOptions& options) {
  SkeletonOptions skeleton = options.skeleton;
  skeleton.initial_radius_m =
      std::max(skeleton.initial_radius_m, options.skeleton_radius_factor * view.spacing_m);
  PointCloud cloud;
  cloud.points_ = L1MedialSkeleton(points, skeleton).points;
  return cloud;
}

std::vector<size_t> AllIndices(size_t n) {
  std::vector<size_t> all(n);
  for (size_t i = 0; i < n; ++i) all[i] = i;
  return all;
}

}  // namespace

bool UsesKeyRegion(CoarseInput input) {
  return input == CoarseInput::kKeyRegion || input == CoarseInput::kKeyRegionSkeleton;
}

double HeightOf(const RegistrationView& view, const Eigen::Vector3d& point, bool use_ground) {
  if (use_ground && view.ground) return view.ground->SignedDistance(point);
  if (view.trunk) return (point - view.trunk->base).dot(TrunkAxis(view));
  return point.dot(view.up);
}

Eigen::Vector3d TrunkAxis(const RegistrationView& view) {
  if (view.trunk && view.trunk->cylinder) return view.trunk->cylinder->axis;
  if (view.trunk) return view.trunk->axis;
  return view.up;
}

std::optional<Eigen::Vector3d> TrunkPointAtHeight(const RegistrationView& view, double height_m,
                                                  bool use_ground) {
  if (!view.trunk) return std::nullopt;
  const Eigen::Vector3d axis = TrunkAxis(view);
  const Eigen::Vector3d on_axis =
      view.trunk->cylinder ? view.trunk->cylinder->point : view.trunk->branch_point;
  // Walk along the axis until the height matches (height is linear along the axis).
  const double h0 = HeightOf(view, on_axis, use_ground);
  const double rate = HeightOf(view, on_axis + axis, use_ground) - h0;
  if (std::abs(rate) < 0.2) return std::nullopt;  // an axis lying nearly flat
  return Eigen::Vector3d(on_axis + axis * ((height_m - h0) / rate));
}

const char* ToString(CoarseInput input) {
  switch (input) {
    case CoarseInput::kEntireTree:
      return "entire_tree";
    case CoarseInput::kKeyRegion:
      return "key_region";
    case CoarseInput::kTreeSkeleton:
      return "tree_skeleton";
    case CoarseInput::kKeyRegionSkeleton:
      return "key_region_skeleton";
  }
  return "?";
}

CoarseInput ParseCoarseInput(const std::string& name) {
  for (CoarseInput input : {CoarseInput::kEntireTree, CoarseInput::kKeyRegion,
                            CoarseInput::kTreeSkeleton, CoarseInput::kKeyRegionSkeleton}) {
    if (name == ToString(input)) return input;
  }
  throw InputError("", "coarse input",
                   fmt::format("expected entire_tree, key_region, tree_skeleton or "
                               "key_region_skeleton, got \"{}\"",
                               name));
}

void RegistrationViewOptions::Validate() const {
  CheckPositive("normal_radius_factor", normal_radius_factor);
  CheckAtLeast("normal_max_neighbors", normal_max_neighbors, 1);
  CheckNested("trunk", [&] { trunk.Validate(); });
  CheckNested("cylinder", [&] { cylinder.Validate(); });
  CheckNested("key_region", [&] { key_region.Validate(); });
  CheckNested("skeleton", [&] { skeleton.Validate(); });
  CheckNested("projection", [&] { projection.Validate(); });
  CheckNonNegative("projection_radius_factor", projection_radius_factor);
  CheckNonNegative("projection_shift_trunk_share", projection_shift_trunk_share);
  CheckNonNegative("projection_min_shift_m", projection_min_shift_m);
  CheckPositive("skeleton_input_voxel_factor", skeleton_input_voxel_factor);
  CheckNonNegative("skeleton_radius_factor", skeleton_radius_factor);
  CheckPositive("coarse_voxel_factor", coarse_voxel_factor);
  CheckPositive("feature_normal_factor", feature_normal_factor);
  CheckPositive("feature_radius_factor", feature_radius_factor);
}

RegistrationView PrepareView(const std::string& name,
                             const preprocessing::PreprocessResult& preprocessed,
                             const RegistrationViewOptions& options) {
  options.Validate();
  const auto start = std::chrono::steady_clock::now();
  RegistrationView view;
  view.name = name;
  auto cloud = std::make_shared<PointCloud>(preprocessed.cloud);
  view.cloud = cloud;
  view.up = preprocessed.up.normalized();
  view.ground = preprocessed.ground;
  view.coarse_input = options.coarse_input;
  if (cloud->points_.size() < 20) {
    view.failure = fmt::format("only {} tree points", cloud->points_.size());
    return view;
  }
  view.spacing_m = preprocessing::MedianPointSpacing(*cloud);
  const KDTreeSearchParamHybrid normal_search(options.normal_radius_factor * view.spacing_m,
                                              options.normal_max_neighbors);
  cloud->EstimateCovariances(normal_search);
  cloud->EstimateNormals(normal_search);  // from the covariances just computed
  cloud->OrientNormalsTowardsCameraLocation(Eigen::Vector3d::Zero());
  auto planarity = std::make_shared<std::vector<float>>(cloud->points_.size());
  for (size_t i = 0; i < cloud->points_.size(); ++i) {
    const Eigen::Vector3d l = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cloud->covariances_[i],
                                                                             Eigen::EigenvaluesOnly)
                                  .eigenvalues();
    (*planarity)[i] = l(2) > 0 ? static_cast<float>((l(1) - l(0)) / l(2)) : 0.0f;
  }
  cloud->covariances_.clear();
  view.planarity = planarity;
  view.cloud_tree = std::make_shared<open3d::geometry::KDTreeFlann>(*cloud);

  const bool needs_key_region = UsesKeyRegion(options.coarse_input);
  std::string why;
  view.trunk = FindTrunk(*cloud, view.up, view.spacing_m, options.trunk, &why);
  if (!view.ground && view.trunk) {
    // Without a ground the camera's -y is only roughly up (the camera pitches); the trunk's axis
    // is the better estimate, and the slices are cut again across it.
    view.up = view.trunk->axis;
    if (auto again = FindTrunk(*cloud, view.up, view.spacing_m, options.trunk, &why)) {
      view.trunk = again;
    }
  }
  if (view.trunk) {
    view.trunk->cylinder = FitTrunkCylinder(*cloud, *view.trunk, options.cylinder);
    view.key_region = KeyRegionOf(*view.trunk, *cloud, view.up, options.key_region);
  } else if (needs_key_region) {
    view.failure = why;
  }

  // The coarse points of the whole view; a pair picks those inside its key regions.
  if (view.CanRegister()) {
    auto medial = std::make_shared<PointCloud>();
    medial->points_ = MedialPoints(view, AllIndices(cloud->points_.size()), options);
    view.medial = medial;
    view.medial_tree = std::make_shared<open3d::geometry::KDTreeFlann>(*medial);
    const bool skeleton = options.coarse_input == CoarseInput::kTreeSkeleton ||
                          options.coarse_input == CoarseInput::kKeyRegionSkeleton;
    if (skeleton) {
      view.coarse = SkeletonCloud(
          view, options.medial_projection ? medial->points_ : cloud->points_, options);
    } else {
      view.coarse = *cloud->VoxelDownSample(options.coarse_voxel_factor * view.spacing_m);
    }
    view.coarse.normals_.clear();
    view.coarse.colors_.clear();
    view.coarse.covariances_.clear();
    if (view.coarse.points_.size() < 5) {
      view.failure = fmt::format("only {} points to align coarsely in the {}",
                                 view.coarse.points_.size(), ToString(options.coarse_input));
    } else {
      ComputeFeatures(view, skeleton, options);
    }
  }
  view.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return view;
}

std::vector<RegistrationView> PrepareViews(
    const std::vector<preprocessing::PreprocessedView>& preprocessed,
    const RegistrationViewOptions& options) {
  options.Validate();
  std::vector<RegistrationView> views(preprocessed.size());
  Progress progress("prepare", static_cast<int64_t>(views.size()), "views");
  oneapi::tbb::parallel_for(size_t{0}, views.size(), [&](size_t v) {
    if (preprocessed[v].result) {
      views[v] = PrepareView(preprocessed[v].name, *preprocessed[v].result, options);
    } else {
      views[v].name = preprocessed[v].name;
      views[v].failure = preprocessed[v].failure;
    }
    progress.Advance();
  });
  return views;
}

}  // namespace simtree::registration
