#include "simtree/synth/detail/tree_pose.h"

#include <algorithm>

namespace simtree::synth {
namespace {

// The segment of `branch` that rest arc length `s` falls on and the fraction along it.
std::pair<int, double> LocateOnRestBranch(const Branch& branch, double s) {
  const int n = static_cast<int>(branch.nodes.size());
  double start = 0.0;
  for (int i = 1; i < n; ++i) {
    const double length = (branch.nodes[i].position - branch.nodes[i - 1].position).norm();
    if (s <= start + length || i == n - 1) {
      const double t = length > 0 ? std::clamp((s - start) / length, 0.0, 1.0) : 0.0;
      return {i - 1, t};
    }
    start += length;
  }
  return {0, 0.0};
}

}  // namespace

TreePose::TreePose(const Tree& tree) {
  offsets_.reserve(tree.branches.size() + 1);
  offsets_.push_back(0);
  for (const Branch& branch : tree.branches) {
    for (const Node& node : branch.nodes) positions_.push_back(node.position);
    offsets_.push_back(static_cast<int>(positions_.size()));
  }
}

Eigen::Vector3d TreePose::PointAt(const Tree& tree, int branch, double arc_length) const {
  const Branch& b = tree.branches[branch];
  if (b.nodes.size() < 2) return node(branch, 0);
  const auto [segment, t] = LocateOnRestBranch(b, arc_length);
  return (1.0 - t) * node(branch, segment) + t * node(branch, segment + 1);
}

Eigen::Vector3d TreePose::TangentAt(const Tree& tree, int branch, double arc_length) const {
  const Branch& b = tree.branches[branch];
  if (b.nodes.size() < 2) return Eigen::Vector3d::UnitZ();
  const int segment = LocateOnRestBranch(b, arc_length).first;
  const Eigen::Vector3d d = node(branch, segment + 1) - node(branch, segment);
  const double length = d.norm();
  return length > 0 ? Eigen::Vector3d(d / length) : Eigen::Vector3d::UnitZ();
}

}  // namespace simtree::synth
