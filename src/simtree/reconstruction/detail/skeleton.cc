#include "simtree/reconstruction/detail/skeleton.h"

#include <algorithm>

namespace simtree::reconstruction {

std::vector<std::vector<int>> Skeleton::Children() const {
  std::vector<std::vector<int>> children(nodes.size());
  for (int i = 1; i < size(); ++i) {
    if (nodes[i].parent >= 0) children[nodes[i].parent].push_back(i);
  }
  return children;
}

std::vector<double> Skeleton::SubtreeLengths() const {
  std::vector<double> length(nodes.size(), 0.0);
  // Children come after parents, so one backward pass accumulates every subtree.
  for (int i = size() - 1; i > 0; --i) {
    const int p = nodes[i].parent;
    if (p < 0) continue;
    length[p] += length[i] + (nodes[i].position - nodes[p].position).norm();
  }
  return length;
}

double Skeleton::TotalLength() const {
  double total = 0.0;
  for (int i = 1; i < size(); ++i) {
    if (nodes[i].parent >= 0) total += (nodes[i].position - nodes[nodes[i].parent].position).norm();
  }
  return total;
}

Skeleton Skeleton::Without(const std::vector<char>& remove) const {
  Skeleton kept;
  std::vector<int> new_index(nodes.size(), -1);
  for (int i = 0; i < size(); ++i) {
    if (remove[i]) continue;
    SkeletonNode node = nodes[i];
    node.parent = node.parent >= 0 ? new_index[node.parent] : -1;
    new_index[i] = kept.size();
    kept.nodes.push_back(node);
  }
  return kept;
}

std::vector<int> HeaviestPath(const Skeleton& skeleton) {
  std::vector<int> path;
  if (skeleton.empty()) return path;
  const auto children = skeleton.Children();
  const std::vector<double> below = skeleton.SubtreeLengths();
  auto carried = [&](int c) {
    return below[c] +
           (skeleton.nodes[c].position - skeleton.nodes[skeleton.nodes[c].parent].position).norm();
  };
  for (int at = 0;;) {
    path.push_back(at);
    if (children[at].empty()) break;
    at = *std::max_element(children[at].begin(), children[at].end(),
                           [&](int a, int b) { return carried(a) < carried(b); });
  }
  return path;
}

std::vector<SkeletonChain> SkeletonChains(const Skeleton& skeleton) {
  std::vector<SkeletonChain> chains;
  if (skeleton.empty()) return chains;
  const auto children = skeleton.Children();
  // Depth-first from the root: every fork (or the root) starts one chain per child.
  std::vector<int> starts = {0};
  while (!starts.empty()) {
    const int start = starts.back();
    starts.pop_back();
    for (const int first : children[start]) {
      SkeletonChain chain;
      chain.nodes = {start, first};
      int at = first;
      while (children[at].size() == 1) {
        at = children[at][0];
        chain.nodes.push_back(at);
      }
      if (children[at].size() > 1) starts.push_back(at);
      chains.push_back(std::move(chain));
    }
  }
  return chains;
}

}  // namespace simtree::reconstruction
