#pragma once
// A branch's mass distribution and modal constants (BranchMechanics) from its material, its
// nodes' radii and its mode shapes.

#include "simtree/core/tree.h"
#include "simtree/dynamics/detail/branch_model.h"

namespace simtree::dynamics {

// `branch` needs a material; `model` and `link` its rest geometry (BuildDynamicsModel);
// `twist_stiffness_ratio` as in DynamicsOptions.
BranchMechanics ComputeBranchMechanics(const Branch& branch, const BranchModel& model,
                                       const BranchLink& link, const NodeTables& nodes,
                                       double twist_stiffness_ratio);

}  // namespace simtree::dynamics
