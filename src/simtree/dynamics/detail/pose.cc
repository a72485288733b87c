#include "simtree/dynamics/detail/pose.h"

#include <algorithm>

#include "simtree/dynamics/detail/mode_shapes.h"

namespace simtree::dynamics {

void PoseBranch(const BranchLink& k, const BranchModel& model, const BranchState* parent,
                BranchState& st) {
  if (parent == nullptr) {
    st.origin = model.rest_base;
    st.frame = model.frame;
    return;
  }
  const BranchState& ps = *parent;
  const std::array<double, 3>& q = ps.modal.q;
  st.origin = ps.origin + ps.frame * LocalOffset(k.attach_au, k.attach_h, k.attach_aw, k.attach_phi,
                                                 k.attach_psi, q);
  st.frame = ps.frame * (RotationFromVector(LocalRotation(k.attach_slope, k.attach_psi, q)) *
                         k.relative_frame);
}

PointOnBranch PointAt(const Branch& branch, const BranchModel& m, double arc_length) {
  PointOnBranch p;
  if (m.length > 0.0) {
    const double x = std::clamp(arc_length / m.length, 0.0, 1.0);
    p.phi = BendingModeShape(x);
    p.slope = BendingModeSlope(x) / m.length;
    p.psi = TwistModeShape(x);
  }
  p.rest_offset = m.frame.transpose() * (branch.PointAt(arc_length) - m.rest_base);
  return p;
}

Eigen::Vector3d PointNow(const DynamicsModel& model, const BranchState& st, int id,
                         double arc_length) {
  const PointOnBranch p = PointAt(model.tree.branches[id], model.models[id], arc_length);
  return st.origin + st.frame * PointLocal(p, st.modal.q);
}

Eigen::Matrix3d NodeRotation(const DynamicsModel& model, const BranchState& st, int id, int j) {
  const BranchLink& k = model.links[id];
  const BranchModel& m = model.models[id];
  const double x = model.nodes.arc_fraction[k.first_node + j];
  const double slope = m.length > 0.0 ? BendingModeSlope(x) / m.length : 0.0;
  const double psi = model.nodes.psi[k.first_node + j];
  return st.frame * RotationFromVector(LocalRotation(slope, psi, st.modal.q)) * m.frame.transpose();
}

}  // namespace simtree::dynamics
