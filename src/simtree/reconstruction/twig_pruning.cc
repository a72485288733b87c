#include "simtree/reconstruction/twig_pruning.h"

#include <algorithm>

namespace simtree {

Skeleton PruneTwigs(const Skeleton& skeleton, const TwigPruningOptions& options,
                    TwigPruningStats* stats) {
  TwigPruningStats local;
  TwigPruningStats& s = stats ? *stats : local;
  s = {};
  Skeleton current = skeleton;
  for (int pass = 0; pass < options.passes; ++pass) {
    const auto children = current.Children();
    std::vector<char> remove(current.nodes.size(), 0);
    int removed = 0;
    for (const SkeletonChain& chain : SkeletonChains(current)) {
      const int fork = chain.nodes.front();
      const int tip = chain.nodes.back();
      // Only twigs: chains that end at a tip and start at a real fork.
      if (!children[tip].empty() || children[fork].size() < 2) continue;
      double support = 0.0, length = 0.0;
      for (size_t k = 1; k < chain.nodes.size(); ++k) {
        const SkeletonNode& node = current.nodes[chain.nodes[k]];
        support += node.support;
        length += (node.position - current.nodes[chain.nodes[k - 1]].position).norm();
      }
      const SkeletonNode& base = current.nodes[fork];
      double thickness = base.thickness;
      if (base.parent >= 0) thickness = std::max(thickness, current.nodes[base.parent].thickness);
      const bool bump = length < options.min_length_per_thickness * thickness;
      const bool sparse = support < options.min_support_per_m * length;
      if (support < options.min_support || length < options.min_length_m || bump || sparse) {
        for (size_t k = 1; k < chain.nodes.size(); ++k) remove[chain.nodes[k]] = 1;
        ++removed;
        s.nodes_removed += static_cast<int>(chain.nodes.size()) - 1;
      }
    }
    if (removed == 0) break;
    s.twigs_removed += removed;
    current = current.Without(remove);
  }
  return current;
}

}  // namespace simtree
