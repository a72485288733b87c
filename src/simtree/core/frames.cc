#include "simtree/core/frames.h"

#include <cmath>

#include <Eigen/Geometry>

namespace simtree {

Frame FrameFromAxes(const Eigen::Vector3d& axis, const Eigen::Vector3d& parent_axis,
                    const Eigen::Vector3d& fallback_u) {
  Frame f;
  f.v = axis.normalized();
  Eigen::Vector3d u = parent_axis.cross(f.v);
  // Below ~0.6 degrees between the axes the plane they span is noise: use the fallback.
  if (u.norm() < 1e-2) {
    u = fallback_u - fallback_u.dot(f.v) * f.v;
    if (u.norm() < 1e-6) u = f.v.unitOrthogonal();
  }
  f.u = u.normalized();
  f.w = f.u.cross(f.v);
  return f;
}

Eigen::Vector3d BranchAxis(const Branch& branch) {
  if (branch.nodes.size() >= 2) {
    const Eigen::Vector3d chord = branch.tip().position - branch.base().position;
    if (chord.norm() > 0.0) return chord.normalized();
  }
  return Eigen::Vector3d::UnitZ();
}

void ComputeFrames(Tree& tree) {
  for (Branch& b : tree.branches) {
    if (b.is_trunk()) {
      b.frame = FrameFromAxes(BranchAxis(b), Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX());
    } else {
      const Frame& parent = tree.branches[b.parent].frame;
      b.frame = FrameFromAxes(BranchAxis(b), parent.v, parent.u);
    }
  }
}

void AssignLevels(Tree& tree) {
  for (Branch& b : tree.branches) {
    b.level = b.is_trunk() ? 0 : tree.branches[b.parent].level + 1;
  }
}

}  // namespace simtree
