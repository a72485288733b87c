#pragma once
// Where a branch and its points are for given modal coordinates. A branch's base rides its
// parent's deformed attachment node: it is carried to that node's position and turned by the
// parent's cross-section there (slope of the bending mode and twist). A point of a branch is its
// rest offset twisted about the chord axis v, then bent by phi (q_u, q_w).

#include <array>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "simtree/dynamics/detail/branch_model.h"
#include "simtree/dynamics/detail/branch_state.h"
#include "simtree/dynamics/detail/rotation.h"

namespace simtree::dynamics {

// The rotation vector, in frame coordinates, of the cross-section at a point whose bending slope
// (per metre) is `slope` and twist shape `psi`, for modal coordinates q.
inline Eigen::Vector3d LocalRotation(double slope, double psi, const std::array<double, 3>& q) {
  return {slope * q[kModeW], psi * q[kModeT], -slope * q[kModeU]};
}

// Offset from the base, in frame coordinates, of a point whose rest offset is (a_u, h, a_w) and
// whose mode shapes are phi, psi: twisted about v, then bent (the node formula).
[[gnu::always_inline]] inline Eigen::Vector3d LocalOffset(double a_u, double h, double a_w,
                                                          double phi, double psi,
                                                          const std::array<double, 3>& q) {
  double s = 0, c = 1;
  SinCos(psi * q[kModeT], &s, &c);
  return {c * a_u + s * a_w + phi * q[kModeU], h, c * a_w - s * a_u + phi * q[kModeW]};
}

// Places a branch (origin and frame of `state`): its base on its parent's deformed attachment
// node, its frame turned by the parent's cross-section there. `parent` is null for the trunk.
void PoseBranch(const BranchLink& link, const BranchModel& model, const BranchState* parent,
                BranchState& state);

// A point of a branch at an arc length: mode-shape values, slope per metre and rest offset (frame
// coordinates).
struct PointOnBranch {
  double phi = 0, slope = 0, psi = 0;
  Eigen::Vector3d rest_offset = Eigen::Vector3d::Zero();
};
PointOnBranch PointAt(const Branch& branch, const BranchModel& model, double arc_length);

// The point's offset from its branch's base (frame coordinates) for modal coordinates q.
inline Eigen::Vector3d PointLocal(const PointOnBranch& p, const std::array<double, 3>& q) {
  return LocalOffset(p.rest_offset.x(), p.rest_offset.y(), p.rest_offset.z(), p.phi, p.psi, q);
}

// A point of branch `id` now (world).
Eigen::Vector3d PointNow(const DynamicsModel& model, const BranchState& state, int id,
                         double arc_length);

// A point's position for the modal coordinates `q_of(branch)` of its branch and ancestors, posed
// from the trunk's rest base (world).
template <typename StateOf>
Eigen::Vector3d PointWith(const DynamicsModel& model, int id, double arc_length,
                          const StateOf& q_of) {
  std::vector<int> chain;
  for (int b = id; b >= 0; b = model.links[b].parent) chain.push_back(b);
  Eigen::Vector3d origin = model.models[chain.back()].rest_base;
  Eigen::Matrix3d frame = model.models[chain.back()].frame;
  for (size_t i = chain.size(); i-- > 1;) {
    const BranchLink& k = model.links[chain[i - 1]];
    const std::array<double, 3> q = q_of(chain[i]);
    origin +=
        frame * LocalOffset(k.attach_au, k.attach_h, k.attach_aw, k.attach_phi, k.attach_psi, q);
    frame = frame *
            (RotationFromVector(LocalRotation(k.attach_slope, k.attach_psi, q)) * k.relative_frame);
  }
  return origin + frame * PointLocal(PointAt(model.tree.branches[id], model.models[id], arc_length),
                                     q_of(id));
}

// Rotation from rest to now of branch `id`'s cross-section at its node j.
Eigen::Matrix3d NodeRotation(const DynamicsModel& model, const BranchState& state, int id, int j);

}  // namespace simtree::dynamics
