#pragma once
// bench_robots' tree: a regular ternary tree (every branch 3 nodes, 3 children at its middle and
// tip) of `branch_count` branches, trunk 3 Hz, branches 1.2 Hz, damping ratio 0.04.

#include <cmath>

#include <Eigen/Geometry>

#include "simtree/core/frames.h"
#include "simtree/core/tree.h"

namespace bench {

inline simtree::Tree TernaryTree(int branch_count) {
  simtree::Tree tree;
  simtree::Branch trunk;
  trunk.nodes = {{Eigen::Vector3d(0, 0, 0), 0.08},
                 {Eigen::Vector3d(0, 0, 0.8), 0.07},
                 {Eigen::Vector3d(0, 0, 1.6), 0.06}};
  tree.branches.push_back(trunk);
  for (int id = 0; static_cast<int>(tree.branches.size()) < branch_count; ++id) {
    const simtree::Branch parent = tree.branches[id];
    const Eigen::Vector3d axis = (parent.tip().position - parent.base().position).normalized();
    const double length = (parent.tip().position - parent.base().position).norm() * 0.7;
    for (int k = 0; k < 3 && static_cast<int>(tree.branches.size()) < branch_count; ++k) {
      const int node = k == 0 ? 1 : 2;
      const double heading = 2.0944 * k + 0.7 * id;
      const Eigen::Vector3d side = axis.unitOrthogonal() * std::cos(heading) +
                                   axis.cross(axis.unitOrthogonal()) * std::sin(heading);
      const Eigen::Vector3d direction = (axis + 0.9 * side).normalized();
      const Eigen::Vector3d base = parent.nodes[node].position;
      const double radius = parent.nodes[node].radius * 0.6;
      simtree::Branch child;
      child.id = static_cast<int>(tree.branches.size());
      child.parent = id;
      child.parent_node = node;
      child.nodes = {{base, radius},
                     {base + 0.5 * length * direction, 0.8 * radius},
                     {base + length * direction, 0.6 * radius}};
      tree.branches.push_back(child);
    }
  }
  simtree::AssignLevels(tree);
  simtree::ComputeFrames(tree);
  for (simtree::Branch& b : tree.branches) {
    b.material = simtree::Material::FromFrequencyDampingStiffness(
        b.is_trunk() ? 3.0 : 1.2, 0.04, b.is_trunk() ? 5000.0 : 50.0,
        simtree::MaterialSource::kAssumed);
  }
  return tree;
}

}  // namespace bench
