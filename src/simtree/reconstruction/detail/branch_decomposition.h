#pragma once
// From a skeleton graph to the simtree branch hierarchy. Starting at the root, a branch follows
// one child at every fork (its continuation) and every other child starts a new branch one level
// deeper, attached to the fork's node. The continuation is the child carrying the most wood (the
// largest subtree length); when another child carries nearly as much, the straighter path wins,
// which is how a person would trace a leader through a fork of two equal stems.

#include <string>

#include "simtree/core/tree.h"
#include "simtree/reconstruction/detail/skeleton.h"

namespace simtree::reconstruction {

struct BranchDecompositionOptions {
  // A child whose subtree is at least this share of the largest competes on straightness (above
  // 1: the heaviest child always continues).
  double comparable_share = 0.7;
  // Nodes (after the fork) over which a path's direction is measured for straightness.
  int straightness_nodes = 4;

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

// The tree (ids in depth-first order, levels and frames set). Every branch has at least two
// nodes; a child's first node repeats its parent's fork node. Radii come from the skeleton.
Tree DecomposeIntoBranches(const Skeleton& skeleton, const BranchDecompositionOptions& options = {},
                           const std::string& source = "");

}  // namespace simtree::reconstruction
