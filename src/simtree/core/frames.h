#pragma once
// Local branch frames (u, v, w) of paper Fig. 9 and the hierarchy bookkeeping that goes with them.

#include "simtree/core/tree.h"

namespace simtree {

// The frame of a branch whose axis runs along `axis` and whose parent's axis is `parent_axis`:
// v is the axis, u is normal to the plane of the branch and its parent (parent_axis x v), and
// w = u x v lies in that plane. When the two axes are (nearly) parallel, u is `fallback_u` made
// perpendicular to v. The trunk uses world X as the fallback and world Z as its parent axis.
Frame FrameFromAxes(const Eigen::Vector3d& axis, const Eigen::Vector3d& parent_axis,
                    const Eigen::Vector3d& fallback_u);

// The axis of a branch: from its base to its tip (the chord), or +Z for a branch of zero length.
Eigen::Vector3d BranchAxis(const Branch& branch);

// Recomputes every branch's frame from its geometry and its parent's frame (parents first).
void ComputeFrames(Tree& tree);

// Sets every branch's level from its parent (trunk 0). Parents must come before children.
void AssignLevels(Tree& tree);

}  // namespace simtree
