#include "simtree/preprocessing/preprocess_view.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <random>

#include <fmt/format.h>
#include <open3d/geometry/KDTreeFlann.h>
#include <spdlog/spdlog.h>
#include <Eigen/Eigenvalues>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/statistics.h"
#include "simtree/preprocessing/point_spacing.h"

namespace simtree::preprocessing {
namespace {

using open3d::geometry::PointCloud;

// The points of `cloud` at `indices`, with their colours and normals.
PointCloud Select(const PointCloud& cloud, const std::vector<size_t>& indices) {
  return *cloud.SelectByIndex(indices);
}

// Least-squares plane through `points`: unit normal and offset (normal . x + offset = 0).
std::pair<Eigen::Vector3d, double> FitPlane(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) covariance += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Eigen::Vector3d normal = solver.eigenvectors().col(0).normalized();
  return {normal, -normal.dot(mean)};
}

}  // namespace

void PreprocessOptions::Validate() const {
  CheckPositive("ground_search_band_m", ground_search_band_m);
  CheckNonNegative("ground_noise_sigmas", ground_noise_sigmas);
  CheckNonNegative("min_ground_band_m", min_ground_band_m);
  CheckInRange("max_ground_tilt_deg", max_ground_tilt_deg, 0.0, 90.0);
  CheckPositive("ground_ransac_iterations", ground_ransac_iterations);
  CheckPositive("ground_sample_points", static_cast<double>(ground_sample_points));
  CheckShare("min_ground_share", min_ground_share);
  CheckNonNegative("outlier_neighbors", outlier_neighbors);
  CheckPositive("outlier_std_ratio", outlier_std_ratio);
  CheckNonNegative("voxel_size_m", voxel_size_m);
  CheckPositive("voxel_spacing_factor", voxel_spacing_factor);
  CheckPositive("cluster_link_factor", cluster_link_factor);
  CheckNonNegative("cluster_attach_distance_m", cluster_attach_distance_m);
}

double PreprocessResult::DownsampleRemovedShare() const {
  const size_t before = input_points - ground_points - outlier_points;
  if (before == 0) return 0.0;
  return 1.0 - static_cast<double>(downsampled_points) / static_cast<double>(before);
}

std::optional<GroundPlane> FindGroundPlane(const PointCloud& cloud,
                                           const PreprocessOptions& options) {
  options.Validate();
  const size_t n = cloud.points_.size();
  if (n < 3) return std::nullopt;
  std::mt19937_64 rng(options.seed);
  std::vector<Eigen::Vector3d> sample;
  if (n <= options.ground_sample_points) {
    sample = cloud.points_;
  } else {
    std::uniform_int_distribution<size_t> pick(0, n - 1);
    sample.reserve(options.ground_sample_points);
    for (size_t i = 0; i < options.ground_sample_points; ++i)
      sample.push_back(cloud.points_[pick(rng)]);
  }
  const Eigen::Vector3d camera_up = -Eigen::Vector3d::UnitY();
  const double min_cos_tilt = std::cos(options.max_ground_tilt_deg * std::numbers::pi / 180.0);
  std::uniform_int_distribution<size_t> pick(0, sample.size() - 1);

  // RANSAC over planes that could be the ground (a tilted wall or a trunk never qualifies).
  size_t best_inliers = 0;
  int64_t best_score = 0;
  Eigen::Vector3d best_normal = Eigen::Vector3d::Zero();
  double best_offset = 0.0;
  for (int iteration = 0; iteration < options.ground_ransac_iterations; ++iteration) {
    const Eigen::Vector3d& a = sample[pick(rng)];
    const Eigen::Vector3d& b = sample[pick(rng)];
    const Eigen::Vector3d& c = sample[pick(rng)];
    Eigen::Vector3d normal = (b - a).cross(c - a);
    const double norm = normal.norm();
    if (norm < 1e-9) continue;
    normal /= norm;
    if (std::abs(normal.dot(camera_up)) < min_cos_tilt) continue;
    if (normal.dot(camera_up) < 0) normal = -normal;
    const double offset = -normal.dot(a);
    // The ground has the scene above it: points below the band count against a plane, so a
    // plane cutting through the tree loses to the one under it.
    int64_t inliers = 0, below = 0;
    for (const auto& p : sample) {
      const double distance = normal.dot(p) + offset;
      if (std::abs(distance) < options.ground_search_band_m) {
        ++inliers;
      } else if (distance < 0) {
        ++below;
      }
    }
    const int64_t score = inliers - 2 * below;
    if (score > best_score) {
      best_score = score;
      best_inliers = static_cast<size_t>(inliers);
      best_normal = normal;
      best_offset = offset;
    }
  }
  if (best_inliers < 3 || static_cast<double>(best_inliers) <
                              options.min_ground_share * static_cast<double>(sample.size())) {
    return std::nullopt;
  }

  // Refine on every point of the cloud inside the search band, then measure the noise.
  std::vector<Eigen::Vector3d> band;
  for (const auto& p : cloud.points_) {
    if (std::abs(best_normal.dot(p) + best_offset) < options.ground_search_band_m)
      band.push_back(p);
  }
  auto [normal, offset] = FitPlane(band);
  if (offset < 0) {  // the camera (the origin) is above the ground
    normal = -normal;
    offset = -offset;
  }
  if (normal.dot(camera_up) < min_cos_tilt) return std::nullopt;
  std::vector<double> residuals;
  residuals.reserve(band.size());
  for (const auto& p : band) residuals.push_back(std::abs(normal.dot(p) + offset));
  GroundPlane ground;
  ground.normal = normal;
  ground.offset = offset;
  ground.noise_m = 1.4826 * UpperMedian(residuals, 0.0);
  ground.points = band.size();
  return ground;
}

PreprocessResult PreprocessView(const PointCloud& camera_cloud, const PreprocessOptions& options,
                                const std::string& source) {
  options.Validate();
  const auto start = std::chrono::steady_clock::now();
  PreprocessResult result;
  result.input_points = camera_cloud.points_.size();
  if (camera_cloud.points_.empty()) {
    throw InputError(source, "", "expected a view with points, got none (no valid depth)");
  }
  std::vector<size_t> finite;
  finite.reserve(camera_cloud.points_.size());
  for (size_t i = 0; i < camera_cloud.points_.size(); ++i) {
    if (camera_cloud.points_[i].allFinite()) finite.push_back(i);
  }
  if (finite.empty()) {
    throw InputError(source, "", "expected finite point coordinates, got only NaN or infinity");
  }
  if (finite.size() < camera_cloud.points_.size()) {
    spdlog::warn("{}: dropped {} points with non-finite coordinates", source,
                 camera_cloud.points_.size() - finite.size());
  }
  PointCloud cloud = Select(camera_cloud, finite);
  result.input_points = cloud.points_.size();

  // Ground.
  if (options.remove_ground) {
    result.ground = FindGroundPlane(cloud, options);
    if (result.ground) {
      result.up = result.ground->normal;
      const double band =
          std::max(options.min_ground_band_m, options.ground_noise_sigmas * result.ground->noise_m);
      std::vector<size_t> above;
      for (size_t i = 0; i < cloud.points_.size(); ++i) {
        if (result.ground->SignedDistance(cloud.points_[i]) > band) above.push_back(i);
      }
      result.ground_points = cloud.points_.size() - above.size();
      cloud = Select(cloud, above);
    }
  }
  if (cloud.points_.size() < options.min_tree_points) {
    throw InputError(source, "",
                     fmt::format("expected a tree above the ground, got {} points off the ground",
                                 cloud.points_.size()));
  }

  // Outliers.
  if (options.outlier_neighbors > 0) {
    auto [kept, indices] =
        cloud.RemoveStatisticalOutliers(options.outlier_neighbors, options.outlier_std_ratio);
    result.outlier_points = cloud.points_.size() - indices.size();
    cloud = std::move(*kept);
  }

  // Voxel grid at a multiple of the measured spacing.
  result.point_spacing_m = MedianPointSpacing(cloud, {.seed = options.seed});
  result.voxel_size_m = options.voxel_size_m > 0
                            ? options.voxel_size_m
                            : options.voxel_spacing_factor * result.point_spacing_m;
  if (!(result.voxel_size_m > 0)) {
    throw InputError(source, "", "expected distinct points to measure their spacing");
  }
  cloud = *cloud.VoxelDownSample(result.voxel_size_m);
  result.downsampled_points = cloud.points_.size();

  // The tree's cluster.
  if (options.keep_tree_cluster && cloud.points_.size() > 1) {
    const std::vector<int> labels =
        cloud.ClusterDBSCAN(options.cluster_link_factor * result.voxel_size_m, 1);
    const int clusters = labels.empty() ? 0 : *std::max_element(labels.begin(), labels.end()) + 1;
    if (clusters > 1) {
      std::vector<size_t> sizes(clusters, 0);
      for (int label : labels) {
        if (label >= 0) ++sizes[label];
      }
      const int largest =
          static_cast<int>(std::max_element(sizes.begin(), sizes.end()) - sizes.begin());
      std::vector<size_t> main_indices;
      for (size_t i = 0; i < labels.size(); ++i) {
        if (labels[i] == largest) main_indices.push_back(i);
      }
      const PointCloud main = Select(cloud, main_indices);
      open3d::geometry::KDTreeFlann main_tree(main);
      // A cluster stays when any of its points is near the tree.
      std::vector<char> attached(clusters, 0);
      attached[largest] = 1;
      std::vector<int> index(1);
      std::vector<double> squared(1);
      const double attach2 = options.cluster_attach_distance_m * options.cluster_attach_distance_m;
      for (size_t i = 0; i < labels.size(); ++i) {
        const int label = labels[i];
        if (label < 0 || attached[label]) continue;
        if (main_tree.SearchKNN(cloud.points_[i], 1, index, squared) > 0 && squared[0] < attach2) {
          attached[label] = 1;
        }
      }
      std::vector<size_t> keep;
      for (size_t i = 0; i < labels.size(); ++i) {
        if (labels[i] >= 0 && attached[labels[i]]) keep.push_back(i);
      }
      result.off_tree_points = cloud.points_.size() - keep.size();
      cloud = Select(cloud, keep);
    }
  }
  result.cloud = std::move(cloud);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace simtree::preprocessing
