#pragma once
// A pose of a tree: where every node is at one instant. It is what the FEM oracle hands the
// virtual sensor (one pose per camera frame) and how scenes move a tree between views.
//
// Nodes are kept branch by branch in id order, base to tip: the order of the tree file and of
// `nodes.bin`. A child's first node is its own entry (it repeats its parent's attachment node),
// and a deformed pose keeps the two together. Radii do not change.

#include <span>
#include <vector>

#include <Eigen/Core>

#include "simtree/core/tree.h"

namespace simtree::synth {

class TreePose {
 public:
  TreePose() = default;
  // The rest pose of `tree`: every node where the tree file puts it.
  explicit TreePose(const Tree& tree);

  int branch_count() const { return static_cast<int>(offsets_.size()) - 1; }
  int node_count() const { return static_cast<int>(positions_.size()); }
  // Index of branch b's first node in positions().
  int offset(int branch) const { return offsets_[branch]; }
  int node_count(int branch) const { return offsets_[branch + 1] - offsets_[branch]; }

  const Eigen::Vector3d& node(int branch, int index) const {
    return positions_[offsets_[branch] + index];
  }
  Eigen::Vector3d& node(int branch, int index) { return positions_[offsets_[branch] + index]; }
  std::span<const Eigen::Vector3d> positions() const { return positions_; }
  std::span<Eigen::Vector3d> positions() { return positions_; }

  // The point of `branch` at a *rest* arc length from its base (what a marker's arc_length
  // means), linearly interpolated between this pose's nodes. `tree` must be the tree this pose
  // was made from.
  Eigen::Vector3d PointAt(const Tree& tree, int branch, double arc_length) const;
  // Unit tangent of `branch` at a rest arc length (the direction of the segment it falls on).
  Eigen::Vector3d TangentAt(const Tree& tree, int branch, double arc_length) const;

 private:
  std::vector<int> offsets_;  // branch_count + 1 entries
  std::vector<Eigen::Vector3d> positions_;
};

}  // namespace simtree::synth
