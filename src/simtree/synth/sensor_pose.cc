#include "simtree/synth/sensor_pose.h"

#include "simtree/core/error.h"

namespace simtree {

Eigen::Isometry3d LookAtCamera(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                               const Eigen::Vector3d& up) {
  const Eigen::Vector3d forward = target - eye;
  if (!eye.allFinite() || !target.allFinite() || !up.allFinite() || forward.norm() < 1e-9) {
    throw InputError("<memory>", "camera look-at", "expected a finite eye distinct from target");
  }
  const Eigen::Vector3d z = forward.normalized();
  const Eigen::Vector3d x_raw = z.cross(up);
  if (x_raw.norm() < 1e-9) {
    throw InputError("<memory>", "camera look-at", "expected a view direction not along `up`");
  }
  const Eigen::Vector3d x = x_raw.normalized();
  const Eigen::Vector3d y = z.cross(x);  // down in the image
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear().col(0) = x;
  pose.linear().col(1) = y;
  pose.linear().col(2) = z;
  pose.translation() = eye;
  return pose;
}

void ValidateCameraPose(const Eigen::Isometry3d& world_from_camera, const std::string& source) {
  const Eigen::Matrix4d& m = world_from_camera.matrix();
  if (!m.allFinite()) {
    throw InputError(source, "world_from_camera", "expected finite numbers, got NaN or infinity");
  }
  if (!m.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1), 1e-12)) {
    throw InputError(source, "world_from_camera", "expected a last row 0 0 0 1");
  }
  const Eigen::Matrix3d r = world_from_camera.linear();
  if (!(r.transpose() * r).isIdentity(1e-6) || r.determinant() < 0.0) {
    throw InputError(source, "world_from_camera", "expected a rotation (orthonormal, det +1)");
  }
}

}  // namespace simtree
