#pragma once
// Ropes on a live simulation: the force a rope pulls with now, and the tension a rope that pulls
// by a displacement needs.

#include <span>

#include <Eigen/Core>

#include "simtree/dynamics/detail/branch_model.h"
#include "simtree/dynamics/detail/branch_state.h"
#include "simtree/dynamics/rope.h"

namespace simtree::dynamics {

struct RopeSlot {
  Rope rope;
  double arc_length = 0;  // on its branch (m), resolved from rope.arc_length
  double tension = 0;     // N
};

// The rope's force on its branch now (N, world): its tension towards the anchor.
Eigen::Vector3d RopeForce(const DynamicsModel& model, std::span<const BranchState> states,
                          const RopeSlot& slot);

// The tension the rope pulls with: its force, or for a displacement rope the tension that
// displaces its point statically by that much towards the anchor, the compliance along the rope
// coming from the static response to a probe force around the state now. Throws InputError when
// the point cannot move towards the anchor.
double RopeTension(const DynamicsModel& model, std::span<const BranchState> states,
                   bool transfer_loads, const RopeSlot& slot);

}  // namespace simtree::dynamics
