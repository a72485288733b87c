#pragma once
// The skeleton a reconstruction grows: a rooted tree of nodes (the root is the trunk base), each
// with its parent, a radius once radii are known, and how many scan points it explains. Space
// colonization writes it; pruning, smoothing, radii and the branch decomposition read and edit it.

#include <vector>

#include <Eigen/Core>

namespace simtree::reconstruction {

struct SkeletonNode {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // metres, world frame
  int parent = -1;                                     // -1 for the root only
  double radius = 0.0;                                 // metres; 0 until radii are assigned
  double support = 0.0;    // scan points this node explains (attraction points it reached)
  double thickness = 0.0;  // spread of those points around the axis (metres), a radius hint
};

struct Skeleton {
  std::vector<SkeletonNode> nodes;  // node 0 is the root; a parent always comes before its child

  bool empty() const { return nodes.empty(); }
  int size() const { return static_cast<int>(nodes.size()); }
  std::vector<std::vector<int>> Children() const;
  // Length of the edges below each node (its subtree), the node's own edge to its parent
  // excluded.
  std::vector<double> SubtreeLengths() const;
  double TotalLength() const;
  // The skeleton without the nodes flagged in `remove` (a removed node's whole subtree must be
  // flagged too); order and parent links of the kept nodes are preserved.
  Skeleton Without(const std::vector<char>& remove) const;
};

// The path from the root that always follows the child carrying the most skeleton below it: the
// trunk and its leader.
std::vector<int> HeaviestPath(const Skeleton& skeleton);

// The chains of a skeleton: maximal paths whose inner nodes have exactly one child. Each chain
// starts at the root or at a fork and ends at a fork or a tip; `nodes` includes both ends.
struct SkeletonChain {
  std::vector<int> nodes;
};
std::vector<SkeletonChain> SkeletonChains(const Skeleton& skeleton);

}  // namespace simtree::reconstruction
