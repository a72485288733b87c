#include "simtree/synth/detail/sensor_pose.h"

#include "simtree/core/error.h"

namespace simtree::synth {

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

}  // namespace simtree::synth
