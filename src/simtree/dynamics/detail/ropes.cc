#include "simtree/dynamics/detail/ropes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/dynamics/detail/loads.h"
#include "simtree/dynamics/detail/modal_step.h"
#include "simtree/dynamics/detail/pose.h"

namespace simtree::dynamics {
namespace {

double TensionForDisplacement(const DynamicsModel& model, std::span<const BranchState> states,
                              bool transfer_loads, const RopeSlot& slot) {
  const int id = slot.rope.branch;
  const Eigen::Vector3d point = PointNow(model, states[id], id, slot.arc_length);
  const Eigen::Vector3d to_anchor = slot.rope.anchor - point;
  if (to_anchor.norm() < 1e-9 || slot.rope.displacement_m == 0.0) return 0.0;
  const Eigen::Vector3d direction = to_anchor.normalized();
  std::vector<Load> probe(model.size());
  std::vector<int> touched;
  WalkPointLoad(model, states, transfer_loads, {id, slot.arc_length, direction}, probe, &touched);
  std::map<int, std::array<double, 3>> dq;
  double largest = 0.0;
  for (int b : touched) {
    const std::array<double, 3> q = StaticDeflection(model.models[b].mechanics, probe[b].q);
    for (int i = 0; i < 3; ++i) largest = std::max(largest, std::abs(q[i]));
    dq[b] = q;
  }
  if (largest == 0.0) {
    throw InputError("rope", "displacement_m",
                     fmt::format("the point at {:.4g} m on branch {} cannot move towards the "
                                 "anchor, so no tension displaces it",
                                 slot.arc_length, id));
  }
  // Linearise around the state now with a probe small enough to stay linear.
  const double epsilon = 1e-6 / largest;
  const auto moved = [&](int b) {
    std::array<double, 3> q = states[b].modal.q;
    if (auto it = dq.find(b); it != dq.end()) {
      for (int i = 0; i < 3; ++i) q[i] += epsilon * it->second[i];
    }
    return q;
  };
  const auto now = [&](int b) { return states[b].modal.q; };
  const Eigen::Vector3d displaced = PointWith(model, id, slot.arc_length, moved);
  const Eigen::Vector3d here = PointWith(model, id, slot.arc_length, now);
  const double compliance = (displaced - here).dot(direction) / epsilon;  // m per N
  if (!(compliance > 0.0)) {
    throw InputError("rope", "displacement_m",
                     fmt::format("the point at {:.4g} m on branch {} does not move towards the "
                                 "anchor when pulled",
                                 slot.arc_length, id));
  }
  return slot.rope.displacement_m / compliance;
}

}  // namespace

Eigen::Vector3d RopeForce(const DynamicsModel& model, std::span<const BranchState> states,
                          const RopeSlot& slot) {
  const int id = slot.rope.branch;
  const Eigen::Vector3d point = PointNow(model, states[id], id, slot.arc_length);
  const Eigen::Vector3d to_anchor = slot.rope.anchor - point;
  const double distance = to_anchor.norm();
  if (distance < 1e-9 || slot.tension == 0.0) return Eigen::Vector3d::Zero();
  return slot.tension / distance * to_anchor;
}

double RopeTension(const DynamicsModel& model, std::span<const BranchState> states,
                   bool transfer_loads, const RopeSlot& slot) {
  return slot.rope.mode == Rope::Mode::kForce
             ? slot.rope.force_n
             : TensionForDisplacement(model, states, transfer_loads, slot);
}

}  // namespace simtree::dynamics
