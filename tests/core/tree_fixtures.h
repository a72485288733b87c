#pragma once
// Small hand-made trees for the core tests.

#include "simtree/core/frames.h"
#include "simtree/core/tree.h"

namespace simtree::test {

// A trunk along +Z (5 nodes, 1 m) with two children at node 2 and one grandchild.
inline Tree SmallTree() {
  Tree tree;
  tree.metadata.species = "test";
  auto add = [&](int parent, int parent_node, Eigen::Vector3d base, Eigen::Vector3d dir, int count,
                 double step, double r0) {
    Branch b;
    b.id = tree.size();
    b.parent = parent;
    b.parent_node = parent_node;
    for (int i = 0; i < count; ++i) {
      b.nodes.push_back({base + dir.normalized() * step * i, r0 * (1.0 - 0.1 * i)});
    }
    tree.branches.push_back(b);
  };
  add(-1, 0, {0, 0, 0}, {0, 0, 1}, 5, 0.25, 0.1);
  add(0, 2, tree.branches[0].nodes[2].position, {1, 0, 1}, 4, 0.2, 0.04);
  add(0, 2, tree.branches[0].nodes[2].position, {-1, 0.5, 1}, 4, 0.2, 0.04);
  add(1, 3, tree.branches[1].nodes[3].position, {1, 1, 0.5}, 3, 0.1, 0.02);
  AssignLevels(tree);
  ComputeFrames(tree);
  return tree;
}

inline Tree SmallTreeWithMaterials() {
  Tree tree = SmallTree();
  for (Branch& b : tree.branches) {
    b.material = Material::FromFrequencyDampingStiffness(
        1.0 + 0.5 * b.level, 0.03, 1000.0 / (1 + b.level), MaterialSource::kMeasured);
  }
  tree.branches[3].material->modes[1].frequency_hz = 2.2;  // modes may differ
  tree.markers.push_back({0, "M0", 0, 0.5, -1, tree.branches[0].PointAt(0.5)});
  tree.markers.push_back({1, "M1", 1, 0.3, 0, tree.branches[1].PointAt(0.3)});
  return tree;
}

}  // namespace simtree::test
