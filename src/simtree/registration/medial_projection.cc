#include "simtree/registration/medial_projection.h"

#include <algorithm>

#include <oneapi/tbb/parallel_for.h>
#include <Eigen/Cholesky>

namespace simtree {

std::vector<Eigen::Vector3d> ProjectToMedialAxes(const open3d::geometry::PointCloud& cloud,
                                                 const open3d::geometry::KDTreeFlann& tree,
                                                 const std::vector<size_t>& indices,
                                                 const MedialProjectionOptions& options) {
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

}  // namespace simtree
