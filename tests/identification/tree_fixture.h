#pragma once
// A small static tree for the identification tests: a trunk, three first-level branches of
// different lengths and radii, two second-level branches; straight, with known geometry.

#include "simtree/core/frames.h"
#include "simtree/core/tree.h"

namespace simtree::test {

inline Branch StraightBranch(int id, int parent, int parent_node, const Eigen::Vector3d& base,
                             const Eigen::Vector3d& direction, double length, double base_radius,
                             double tip_radius, int nodes = 5) {
  Branch b;
  b.id = id;
  b.parent = parent;
  b.parent_node = parent_node;
  for (int i = 0; i < nodes; ++i) {
    const double a = double(i) / (nodes - 1);
    b.nodes.push_back(
        {base + direction.normalized() * length * a, (1 - a) * base_radius + a * tip_radius});
  }
  return b;
}

inline Tree IdentificationTree() {
  Tree tree;
  tree.metadata.species = "test";
  tree.branches.push_back(StraightBranch(0, -1, 0, {0, 0, 0}, {0, 0, 1}, 2.0, 0.08, 0.03));
  auto on = [&](int parent, int node) { return tree.branches[parent].nodes[node].position; };
  tree.branches.push_back(StraightBranch(1, 0, 2, on(0, 2), {1, 0, 1}, 1.2, 0.04, 0.01));
  tree.branches.push_back(StraightBranch(2, 0, 3, on(0, 3), {-1, 0.3, 1}, 0.9, 0.03, 0.008));
  tree.branches.push_back(StraightBranch(3, 0, 3, on(0, 3), {0.2, 1, 0.8}, 0.6, 0.02, 0.006));
  tree.branches.push_back(StraightBranch(4, 1, 2, on(1, 2), {1, 1, 0.5}, 0.5, 0.015, 0.004));
  tree.branches.push_back(StraightBranch(5, 2, 3, on(2, 3), {-1, -1, 0.6}, 0.4, 0.012, 0.004));
  AssignLevels(tree);
  ComputeFrames(tree);
  return tree;
}

}  // namespace simtree::test
