#pragma once
// The per-node work of a step: every node of a branch placed from the branch's pose and modal
// coordinates. With the node's rest offset (h along the chord axis v, (a_u, a_w) across it) and
// its mode-shape values phi (bending) and psi (twist), twisting by t = psi q_t turns (a_u, a_w) by
// t about v, bending adds phi (q_u, q_w), and the branch's pose (o, R) places the result:
//   x = o + h Rv + (cos t a_u + sin t a_w + phi q_u) Ru + (cos t a_w - sin t a_u + phi q_w) Rw
// with Ru, Rv, Rw the branch's deformed frame at its base. Five floats in, three out, ~30 flops:
// the step is bound by memory bandwidth.

#include <Eigen/Core>

#include "simtree/dynamics/detail/branch_model.h"
#include "simtree/dynamics/detail/branch_state.h"

namespace simtree::dynamics {

// Writes the branch's `link.nodes` deformed nodes from positions[link.first_node] on.
void DeformNodes(const NodeTables& nodes, const BranchLink& link, const BranchState& state,
                 Eigen::Vector3f* positions);

}  // namespace simtree::dynamics
