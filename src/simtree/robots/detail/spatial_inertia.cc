#include "simtree/robots/detail/spatial_inertia.h"

namespace simtree::robots::detail {
namespace {

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

}  // namespace

Matrix6d SpatialInertia(double mass, const Eigen::Vector3d& com,
                        const Eigen::Matrix3d& inertia_com) {
  // Kinetic energy of velocity (w, v0): m |v0 + w x c|^2 / 2 + w^T Ic w / 2.
  const Eigen::Matrix3d c = Skew(com);
  Matrix6d out;
  out.topLeftCorner<3, 3>() = inertia_com + mass * c * c.transpose();
  out.topRightCorner<3, 3>() = mass * c;
  out.bottomLeftCorner<3, 3>() = mass * c.transpose();
  out.bottomRightCorner<3, 3>() = mass * Eigen::Matrix3d::Identity();
  return out;
}

Vector6d HingeMotion(const Eigen::Vector3d& axis, const Eigen::Vector3d& point) {
  Vector6d s;
  s.head<3>() = axis;
  s.tail<3>() = point.cross(axis);
  return s;
}

double MassOf(const Matrix6d& inertia) { return inertia(3, 3); }

Eigen::Vector3d FirstMomentOf(const Matrix6d& inertia) {
  // The top-right block is m [c]x: read m c off it.
  const Eigen::Matrix3d mc = inertia.topRightCorner<3, 3>();
  return {mc(2, 1), mc(0, 2), mc(1, 0)};
}

}  // namespace simtree::robots::detail
