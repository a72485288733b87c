#include "simtree/registration/detail/medial_projection.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <oneapi/tbb/parallel_for.h>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "simtree/core/option_checks.h"

namespace simtree::registration {
namespace {

// The axis point of `p` from its branch's silhouette (MedialProjectionOptions::silhouette), or
// nullopt when the neighbourhood is not a branch narrower than it is long.
std::optional<Eigen::Vector3d> SilhouetteAxisPoint(const open3d::geometry::PointCloud& cloud,
                                                   const Eigen::Vector3d& p,
                                                   const std::vector<int>& neighbours,
                                                   const MedialProjectionOptions& options) {
  if (neighbours.size() < 8 || p.norm() <= 0) return std::nullopt;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int j : neighbours) mean += cloud.points_[j];
  mean /= static_cast<double>(neighbours.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (int j : neighbours) {
    const Eigen::Vector3d d = cloud.points_[j] - mean;
    covariance += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  const Eigen::Vector3d axis = eigen.eigenvectors().col(2);
  // Across the axis and the line of sight (the silhouette's width), and along the line of sight
  // without its share along the axis (depth).
  const Eigen::Vector3d sight = p.normalized();
  const Eigen::Vector3d across_raw = axis.cross(sight);
  if (across_raw.norm() < 0.3) return std::nullopt;  // a branch pointing at the camera
  const Eigen::Vector3d across = across_raw.normalized();
  const Eigen::Vector3d depth = (sight - sight.dot(axis) * axis).normalized();
  double low = 0, high = 0, along_low = 0, along_high = 0;
  for (int j : neighbours) {
    const Eigen::Vector3d d = cloud.points_[j] - p;
    low = std::min(low, d.dot(across));
    high = std::max(high, d.dot(across));
    along_low = std::min(along_low, d.dot(axis));
    along_high = std::max(along_high, d.dot(axis));
  }
  const double width = high - low;
  // A branch: longer than wide, and its edges well inside the neighbourhood across (else they
  // may be where the neighbourhood ends).
  if (width > options.silhouette_elongation * (along_high - along_low) ||
      std::max(-low, high) > options.silhouette_containment * options.neighbourhood_m) {
    return std::nullopt;
  }
  const double radius = 0.5 * width;
  const double middle = 0.5 * (low + high);  // the axis's place across, from p
  const double behind = std::sqrt(std::max(0.0, radius * radius - middle * middle));
  return p + middle * across + behind * depth;
}

}  // namespace

void MedialProjectionOptions::Validate() const {
  CheckPositive("neighbourhood_m", neighbourhood_m);
  CheckAtLeast("max_neighbours", max_neighbours, 2);
  CheckNonNegative("max_shift_m", max_shift_m);
  CheckNonNegative("regularisation", regularisation);
  CheckPositive("silhouette_elongation", silhouette_elongation);
  CheckShare("silhouette_containment", silhouette_containment);
  CheckAtLeast("silhouette_max_neighbours", silhouette_max_neighbours, 2);
}

std::vector<Eigen::Vector3d> ProjectToMedialAxes(const open3d::geometry::PointCloud& cloud,
                                                 const open3d::geometry::KDTreeFlann& tree,
                                                 const std::vector<size_t>& indices,
                                                 const MedialProjectionOptions& options) {
  options.Validate();
  std::vector<Eigen::Vector3d> projected(indices.size());
  if (!cloud.HasNormals()) {
    for (size_t k = 0; k < indices.size(); ++k) projected[k] = cloud.points_[indices[k]];
    return projected;
  }
  oneapi::tbb::parallel_for(size_t{0}, indices.size(), [&](size_t k) {
    const Eigen::Vector3d& p = cloud.points_[indices[k]];
    const Eigen::Vector3d& normal = cloud.normals_[indices[k]];
    std::vector<int> neighbours;
    std::vector<double> squared;
    if (options.silhouette) {
      tree.SearchHybrid(p, options.neighbourhood_m, options.silhouette_max_neighbours, neighbours,
                        squared);
      if (auto axis_point = SilhouetteAxisPoint(cloud, p, neighbours, options)) {
        projected[k] = *axis_point;
        return;
      }
    }
    tree.SearchHybrid(p, options.neighbourhood_m, options.max_neighbours, neighbours, squared);
    // Minimise sum_j |(I - n_j n_j^T)(x - p_j)|^2 + lambda |x - p|^2.
    const double lambda = options.regularisation * std::max<size_t>(neighbours.size(), 1);
    Eigen::Matrix3d a = lambda * Eigen::Matrix3d::Identity();
    Eigen::Vector3d b = lambda * p;
    for (int j : neighbours) {
      const Eigen::Vector3d& n = cloud.normals_[j];
      const Eigen::Matrix3d m = Eigen::Matrix3d::Identity() - n * n.transpose();
      a += m;
      b += m * cloud.points_[j];
    }
    Eigen::Vector3d shift = a.ldlt().solve(b) - p;
    if (!shift.allFinite()) shift.setZero();
    // Only inwards, and not further than the thickest branch.
    const double inwards = -shift.dot(normal);
    if (inwards <= 0) {
      shift.setZero();
    } else if (shift.norm() > options.max_shift_m) {
      shift *= options.max_shift_m / shift.norm();
    }
    projected[k] = p + shift;
  });
  return projected;
}

}  // namespace simtree::registration
