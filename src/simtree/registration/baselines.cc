#include "simtree/registration/baselines.h"

#include <chrono>

#include <open3d/pipelines/registration/CorrespondenceChecker.h>
#include <open3d/pipelines/registration/Feature.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/utility/Random.h>
#include <Eigen/Eigenvalues>

#include "simtree/core/option_checks.h"

namespace simtree::registration {
namespace {

namespace reg = open3d::pipelines::registration;
using Clock = std::chrono::steady_clock;

double Since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// A cloud with camera-oriented normals (kept when it has them).
open3d::geometry::PointCloud WithNormals(const open3d::geometry::PointCloud& cloud, double radius) {
  open3d::geometry::PointCloud out = cloud;
  if (!out.HasNormals()) {
    out.EstimateNormals(open3d::geometry::KDTreeSearchParamHybrid(radius, 30));
    out.OrientNormalsTowardsCameraLocation(Eigen::Vector3d::Zero());
  }
  return out;
}

// Centroid and principal axes (columns, largest variance first, right-handed).
std::pair<Eigen::Vector3d, Eigen::Matrix3d> Principal(const open3d::geometry::PointCloud& cloud) {
  const auto [mean, covariance] = cloud.ComputeMeanAndCovariance();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  Eigen::Matrix3d axes;
  axes.col(0) = solver.eigenvectors().col(2);
  axes.col(1) = solver.eigenvectors().col(1);
  axes.col(2) = axes.col(0).cross(axes.col(1));
  return {mean, axes};
}

}  // namespace

void BaselineOptions::Validate() const {
  CheckPositive("spacing_m", spacing_m);
  CheckPositive("feature_voxel_factor", feature_voxel_factor);
  CheckPositive("normal_radius_factor", normal_radius_factor);
  CheckPositive("feature_radius_factor", feature_radius_factor);
  CheckPositive("ransac_distance_factor", ransac_distance_factor);
  CheckAtLeast("ransac_iterations", ransac_iterations, 1);
  CheckShare("ransac_confidence", ransac_confidence);
  CheckPositiveList("icp_distance_factors", icp_distance_factors, true);
  CheckAtLeast("icp_iterations", icp_iterations, 1);
}

Eigen::Isometry3d Open3dIcp(const open3d::geometry::PointCloud& source,
                            const open3d::geometry::PointCloud& target,
                            const Eigen::Isometry3d& initial, const BaselineOptions& options,
                            double* fitness) {
  options.Validate();
  Eigen::Matrix4d transform = initial.matrix();
  reg::RegistrationResult result;
  for (double factor : options.icp_distance_factors) {
    result = reg::RegistrationICP(source, target, factor * options.spacing_m, transform,
                                  reg::TransformationEstimationPointToPlane(),
                                  reg::ICPConvergenceCriteria(1e-6, 1e-6, options.icp_iterations));
    transform = result.transformation_;
  }
  if (fitness) *fitness = result.fitness_;
  return Eigen::Isometry3d(transform);
}

BaselineResult PcaIcp(const open3d::geometry::PointCloud& source_in,
                      const open3d::geometry::PointCloud& target_in,
                      const BaselineOptions& options) {
  options.Validate();
  const auto start = Clock::now();
  const double normal_radius = 3.0 * options.spacing_m;
  const auto source = WithNormals(source_in, normal_radius);
  const auto target = WithNormals(target_in, normal_radius);
  const auto [ms, as] = Principal(source);
  const auto [mt, at] = Principal(target);
  BaselineResult best;
  best.fitness = -1.0;
  // The axes' signs are arbitrary: try the four proper flips, keep the best after ICP.
  const double flips[4][2] = {{1, 1}, {1, -1}, {-1, 1}, {-1, -1}};
  for (const auto& f : flips) {
    Eigen::Matrix3d flipped = at;
    flipped.col(0) *= f[0];
    flipped.col(1) *= f[1];
    flipped.col(2) = flipped.col(0).cross(flipped.col(1));
    Eigen::Isometry3d coarse = Eigen::Isometry3d::Identity();
    coarse.linear() = flipped * as.transpose();
    coarse.translation() = mt - coarse.linear() * ms;
    const double coarse_s = Since(start);
    double fitness = 0.0;
    const Eigen::Isometry3d fine = Open3dIcp(source, target, coarse, options, &fitness);
    if (fitness > best.fitness) {
      best.fitness = fitness;
      best.coarse = coarse;
      best.target_from_source = fine;
      best.coarse_seconds = coarse_s;
    }
  }
  best.seconds = Since(start);
  return best;
}

BaselineResult Open3dFpfhRansacIcp(const open3d::geometry::PointCloud& source_in,
                                   const open3d::geometry::PointCloud& target_in,
                                   const BaselineOptions& options) {
  options.Validate();
  const auto start = Clock::now();
  const double voxel = options.feature_voxel_factor * options.spacing_m;
  auto down = [&](const open3d::geometry::PointCloud& cloud) {
    auto d = cloud.VoxelDownSample(voxel);
    d->normals_.clear();
    d->EstimateNormals(
        open3d::geometry::KDTreeSearchParamHybrid(options.normal_radius_factor * voxel, 30));
    d->OrientNormalsTowardsCameraLocation(Eigen::Vector3d::Zero());
    return d;
  };
  const auto source_down = down(source_in);
  const auto target_down = down(target_in);
  const open3d::geometry::KDTreeSearchParamHybrid feature_search(
      options.feature_radius_factor * voxel, 100);
  const auto source_features = reg::ComputeFPFHFeature(*source_down, feature_search);
  const auto target_features = reg::ComputeFPFHFeature(*target_down, feature_search);
  const double distance = options.ransac_distance_factor * voxel;
  std::vector<std::reference_wrapper<const reg::CorrespondenceChecker>> checkers;
  const reg::CorrespondenceCheckerBasedOnEdgeLength edge(0.9);
  const reg::CorrespondenceCheckerBasedOnDistance close(distance);
  checkers.push_back(edge);
  checkers.push_back(close);
  open3d::utility::random::Seed(options.seed);
  const reg::RegistrationResult coarse = reg::RegistrationRANSACBasedOnFeatureMatching(
      *source_down, *target_down, *source_features, *target_features, /*mutual_filter=*/true,
      distance, reg::TransformationEstimationPointToPoint(false), 3, checkers,
      reg::RANSACConvergenceCriteria(options.ransac_iterations, options.ransac_confidence));
  BaselineResult result;
  result.coarse = Eigen::Isometry3d(coarse.transformation_);
  result.coarse_seconds = Since(start);
  const double normal_radius = 3.0 * options.spacing_m;
  result.target_from_source =
      Open3dIcp(WithNormals(source_in, normal_radius), WithNormals(target_in, normal_radius),
                result.coarse, options, &result.fitness);
  result.seconds = Since(start);
  return result;
}

}  // namespace simtree::registration
