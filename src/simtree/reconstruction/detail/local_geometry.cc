#include "simtree/reconstruction/detail/local_geometry.h"

#include <cmath>

#include <Eigen/Geometry>

namespace simtree::reconstruction {

void PlaneBasis(const Eigen::Vector3d& axis, Eigen::Vector3d* e1, Eigen::Vector3d* e2) {
  const Eigen::Vector3d helper =
      std::abs(axis.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  *e1 = axis.cross(helper).normalized();
  *e2 = axis.cross(*e1);
}

Eigen::Matrix3d NeighbourhoodCovariance(std::span<const Eigen::Vector3d> points,
                                        std::span<const int> ids, Eigen::Vector3d* mean) {
  *mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  if (ids.empty()) return cov;
  for (const int i : ids) *mean += points[i];
  *mean /= static_cast<double>(ids.size());
  for (const int i : ids) cov += (points[i] - *mean) * (points[i] - *mean).transpose();
  return cov / static_cast<double>(ids.size());
}

}  // namespace simtree::reconstruction
