#pragma once
// Small geometric helpers the reconstruction stages share: a basis across an axis, the covariance
// of a neighbourhood.

#include <span>

#include <Eigen/Core>

namespace simtree::reconstruction {

// Two unit vectors that, with the unit `axis`, form a right-handed orthonormal basis
// (e1 x e2 = axis).
void PlaneBasis(const Eigen::Vector3d& axis, Eigen::Vector3d* e1, Eigen::Vector3d* e2);

// Mean and covariance (divided by the count) of points[ids].
Eigen::Matrix3d NeighbourhoodCovariance(std::span<const Eigen::Vector3d> points,
                                        std::span<const int> ids, Eigen::Vector3d* mean);

}  // namespace simtree::reconstruction
