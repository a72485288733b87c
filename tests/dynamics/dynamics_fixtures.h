#pragma once
// Hand-made trees for the dynamics tests, with closed-form answers in mind.

#include <cmath>
#include <string>
#include <vector>

#include "simtree/core/error.h"
#include "simtree/core/frames.h"
#include "simtree/core/tree.h"

namespace simtree::test {

// The field the InputError `fn` throws names ("no error" when it throws none).
template <typename Fn>
std::string InputErrorField(Fn&& fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.where();
  }
  return "no error";
}

// A straight branch from `base` along `direction` with `nodes` nodes over `length` metres.
inline Branch StraightBranch(int id, int parent, int parent_node, const Eigen::Vector3d& base,
                             const Eigen::Vector3d& direction, double length, int nodes,
                             double radius) {
  Branch b;
  b.id = id;
  b.parent = parent;
  b.parent_node = parent_node;
  for (int i = 0; i < nodes; ++i) {
    b.nodes.push_back({base + direction.normalized() * (length * i / (nodes - 1)), radius});
  }
  return b;
}

// One vertical trunk (the whole tree): `length` m, `nodes` nodes, one material.
inline Tree SingleBranchTree(double frequency_hz, double damping, double stiffness,
                             double length = 2.0, int nodes = 21,
                             Eigen::Vector3d direction = Eigen::Vector3d::UnitZ()) {
  Tree tree;
  tree.branches.push_back(StraightBranch(0, -1, 0, {0, 0, 0}, direction, length, nodes, 0.05));
  tree.branches[0].material = Material::FromFrequencyDampingStiffness(
      frequency_hz, damping, stiffness, MaterialSource::kMeasured);
  AssignLevels(tree);
  ComputeFrames(tree);
  return tree;
}

// A vertical trunk (3 m, 31 nodes) with a horizontal child at node 20 and a grandchild at the
// child's tip, plus a second child at node 30 (the trunk tip) leaning the other way.
inline Tree ThreeLevelTree() {
  Tree tree;
  tree.branches.push_back(StraightBranch(0, -1, 0, {0, 0, 0}, {0, 0, 1}, 3.0, 31, 0.1));
  const Eigen::Vector3d n20 = tree.branches[0].nodes[20].position;
  tree.branches.push_back(StraightBranch(1, 0, 20, n20, {1, 0, 0.2}, 1.5, 16, 0.04));
  const Eigen::Vector3d tip1 = tree.branches[1].nodes.back().position;
  tree.branches.push_back(StraightBranch(2, 1, 15, tip1, {0.3, 1, 0.4}, 0.6, 7, 0.015));
  const Eigen::Vector3d n30 = tree.branches[0].nodes[30].position;
  tree.branches.push_back(StraightBranch(3, 0, 30, n30, {-1, 0.4, 1}, 1.0, 11, 0.03));
  AssignLevels(tree);
  ComputeFrames(tree);
  const double f[] = {2.0, 1.4, 1.1, 1.7};
  const double k[] = {20000, 3000, 400, 1500};
  for (int b = 0; b < 4; ++b) {
    tree.branches[b].material =
        Material::FromFrequencyDampingStiffness(f[b], 0.03, k[b], MaterialSource::kMeasured);
  }
  return tree;
}

// A branch bent in a plane: an arc of `nodes` nodes (quarter circle of radius `bend_radius`).
inline Tree CurvedBranchTree() {
  Tree tree;
  Branch b;
  const int nodes = 21;
  const double radius = 1.5;
  for (int i = 0; i < nodes; ++i) {
    const double a = 0.5 * 3.14159265358979 * i / (nodes - 1) * 0.6;
    b.nodes.push_back({{radius * (1 - std::cos(a)), 0.0, radius * std::sin(a)}, 0.04});
  }
  tree.branches.push_back(b);
  AssignLevels(tree);
  ComputeFrames(tree);
  tree.branches[0].material =
      Material::FromFrequencyDampingStiffness(1.5, 0.03, 2000, MaterialSource::kMeasured);
  return tree;
}

// A vertical parent (2 m, 21 nodes) with `twigs` straight twigs (0.4 m) hung from its upper
// half all round it, every twig at the parent's frequency and damping (what a pull test's
// materials give: a twig takes the frequency of the tree's mode it moves in) and of stiffness
// `twig_stiffness` (N/m: a light twig's wood times 4 pi^2 f^2 is a few N/m).
inline Tree TunedTwigTree(int twigs, double twig_stiffness, double frequency_hz = 1.5,
                          double damping = 0.03, double parent_stiffness = 1000) {
  Tree tree;
  tree.branches.push_back(StraightBranch(0, -1, 0, {0, 0, 0}, {0, 0, 1}, 2.0, 21, 0.05));
  for (int i = 1; i <= twigs; ++i) {
    const int node = 10 + (i % 11);
    const double a = 2.4 * i;
    tree.branches.push_back(StraightBranch(i, 0, node, tree.branches[0].nodes[node].position,
                                           {std::cos(a), std::sin(a), 0.3}, 0.4, 9, 0.006));
  }
  AssignLevels(tree);
  ComputeFrames(tree);
  for (Branch& b : tree.branches) {
    b.material = Material::FromFrequencyDampingStiffness(
        frequency_hz, damping, b.id == 0 ? parent_stiffness : twig_stiffness,
        MaterialSource::kInterpolated);
  }
  return tree;
}

}  // namespace simtree::test
