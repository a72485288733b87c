#pragma once
// The exported tree linearised about its rest pose in joint space (one coordinate per hinge):
// the mass matrix M and gravity's stiffness G, the Hessian of the weight's potential. The
// springs add diag(k), so the small motions obey M q'' + C q' + (diag(k) + G) q = 0. G matters:
// a 0.5 Hz twig or an upright trunk feels gravity as a spring of the same order as its own.

#include <vector>

#include <Eigen/Core>

#include "simtree/robots/detail/spatial_inertia.h"
#include "simtree/robots/robot_model.h"

namespace simtree::robots::detail {

struct HingeIndex {
  int segment;
  int hinge;
};

struct JointSpaceModel {
  std::vector<HingeIndex> hinges;  // segment order, then hinge order (MuJoCo's dof order)
  Eigen::MatrixXd mass;            // M
  Eigen::MatrixXd gravity;         // G (zero without gravity)
};

// Gravity's stiffness between two hinges on one path from the root: d2V / dq_p dq_d, the
// distal hinge (axis, point) carrying `carried` (its sub-tree's spatial inertia); gravity along
// -Z of magnitude `gravity`.
double GravityStiffness(const Eigen::Vector3d& proximal_axis, const Eigen::Vector3d& distal_axis,
                        const Eigen::Vector3d& distal_point, const Matrix6d& carried,
                        double gravity);

// `gravity` is the magnitude of gravity along -Z (m/s^2).
JointSpaceModel LineariseRobotModel(const RobotModel& model, double gravity);

}  // namespace simtree::robots::detail
