#pragma once
// Rigid-body inertia in the 6D form (angular first, then linear) about the world origin, so the
// inertias of bodies add, and a hinge's share of a body's kinetic energy is S^T I S with S the
// hinge's motion (its axis, and the velocity it gives the point at the origin).

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace simtree::robots::detail {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

// A body of `mass` with its centre of mass at `com` and inertia `inertia_com` about it.
Matrix6d SpatialInertia(double mass, const Eigen::Vector3d& com,
                        const Eigen::Matrix3d& inertia_com);

// A unit-rate turn about `axis` through `point`: angular velocity axis, origin velocity
// point x axis.
Vector6d HingeMotion(const Eigen::Vector3d& axis, const Eigen::Vector3d& point);

// The total mass and first moment (mass times centre of mass) held in a spatial inertia.
double MassOf(const Matrix6d& inertia);
Eigen::Vector3d FirstMomentOf(const Matrix6d& inertia);

}  // namespace simtree::robots::detail
