#include "simtree/robots/detail/joint_space_model.h"

#include <Eigen/Geometry>

#include "simtree/robots/detail/spatial_inertia.h"

namespace simtree::robots::detail {
namespace {

bool IsAncestorOrSelf(const RobotModel& model, int ancestor, int segment) {
  for (int s = segment; s >= 0; s = model.segments[s].parent) {
    if (s == ancestor) return true;
  }
  return false;
}

std::vector<HingeIndex> FlatHinges(const RobotModel& model) {
  std::vector<HingeIndex> hinges;
  for (size_t s = 0; s < model.segments.size(); ++s) {
    for (size_t h = 0; h < model.segments[s].hinges.size(); ++h) {
      hinges.push_back({static_cast<int>(s), static_cast<int>(h)});
    }
  }
  return hinges;
}

// Every segment's spatial inertia with its sub-tree's.
std::vector<Matrix6d> SubtreeInertias(const RobotModel& model) {
  std::vector<Matrix6d> sub(model.segments.size());
  for (size_t i = 0; i < model.segments.size(); ++i) {
    const Segment& s = model.segments[i];
    sub[i] = SpatialInertia(s.mass_kg, s.center_of_mass, s.inertia);
  }
  for (size_t i = model.segments.size(); i-- > 0;) {
    if (model.segments[i].parent >= 0) sub[model.segments[i].parent] += sub[i];
  }
  return sub;
}

// The more distal of two hinges on one path from the root (the later one in a body, as MuJoCo
// composes a body's joints in order), or -1 when neither carries the other.
int DistalOf(const RobotModel& model, const std::vector<HingeIndex>& hinges, int i, int j) {
  const int si = hinges[i].segment, sj = hinges[j].segment;
  if (si == sj) return hinges[i].hinge >= hinges[j].hinge ? i : j;
  if (IsAncestorOrSelf(model, si, sj)) return j;
  if (IsAncestorOrSelf(model, sj, si)) return i;
  return -1;
}

}  // namespace

double GravityStiffness(const Eigen::Vector3d& proximal_axis, const Eigen::Vector3d& distal_axis,
                        const Eigen::Vector3d& distal_point, const Matrix6d& carried,
                        double gravity) {
  // d2x / dq_p dq_d = a_p x (a_d x (x - p_d)) for every carried point x; the weight's potential
  // is -m g.x with g = (0, 0, -gravity).
  const Eigen::Vector3d lever = FirstMomentOf(carried) - MassOf(carried) * distal_point;
  return gravity * proximal_axis.cross(distal_axis.cross(lever)).z();
}

JointSpaceModel LineariseRobotModel(const RobotModel& model, double gravity) {
  JointSpaceModel out;
  out.hinges = FlatHinges(model);
  const int n = static_cast<int>(out.hinges.size());
  const std::vector<Matrix6d> sub = SubtreeInertias(model);
  std::vector<Vector6d> motion(n);
  std::vector<Eigen::Vector3d> axis(n), point(n);
  for (int i = 0; i < n; ++i) {
    const Segment& s = model.segments[out.hinges[i].segment];
    axis[i] = s.hinges[out.hinges[i].hinge].axis;
    point[i] = s.base;
    motion[i] = HingeMotion(axis[i], point[i]);
  }
  out.mass = Eigen::MatrixXd::Zero(n, n);
  out.gravity = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = i; j < n; ++j) {
      const int distal = DistalOf(model, out.hinges, i, j);
      if (distal < 0) continue;
      const int proximal = distal == i ? j : i;
      // Both hinges swing the bodies beyond the distal one.
      const Matrix6d& carried = sub[out.hinges[distal].segment];
      out.mass(i, j) = out.mass(j, i) = motion[i].dot(carried * motion[j]);
      out.gravity(i, j) = out.gravity(j, i) =
          GravityStiffness(axis[proximal], axis[distal], point[distal], carried, gravity);
    }
  }
  return out;
}

}  // namespace simtree::robots::detail
