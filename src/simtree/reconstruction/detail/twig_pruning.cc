#include "simtree/reconstruction/detail/twig_pruning.h"

#include <algorithm>
#include <cmath>

#include "simtree/core/option_checks.h"
#include "simtree/reconstruction/detail/point_index.h"

namespace simtree::reconstruction {

void TwigPruningOptions::Validate() const {
  CheckNonNegative("min_support", min_support);
  CheckNonNegative("min_support_per_m", min_support_per_m);
  CheckNonNegative("min_length_m", min_length_m);
  CheckNonNegative("min_length_per_thickness", min_length_per_thickness);
  CheckAtLeast("passes", passes, 0);
}

Skeleton PruneTwigs(const Skeleton& skeleton, const TwigPruningOptions& options,
                    TwigPruningStats* stats) {
  options.Validate();
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

Skeleton PruneTwigsInsideWood(const Skeleton& skeleton, double inside_share, int passes,
                              TwigPruningStats* stats) {
  TwigPruningStats local;
  TwigPruningStats& s = stats ? *stats : local;
  s = {};
  Skeleton current = skeleton;
  std::vector<int> near;
  std::vector<double> d2;
  for (int pass = 0; pass < passes; ++pass) {
    const auto children = current.Children();
    std::vector<Eigen::Vector3d> positions(current.nodes.size());
    for (int i = 0; i < current.size(); ++i) positions[i] = current.nodes[i].position;
    const PointIndex index(positions);
    const std::vector<SkeletonChain> chains = SkeletonChains(current);
    std::vector<int> chain_of(current.nodes.size(), -1);
    for (size_t c = 0; c < chains.size(); ++c) {
      for (size_t k = 1; k < chains[c].nodes.size(); ++k) chain_of[chains[c].nodes[k]] = c;
    }
    std::vector<char> remove(current.nodes.size(), 0);
    int removed = 0;
    for (size_t c = 0; c < chains.size(); ++c) {
      const auto& ids = chains[c].nodes;
      if (!children[ids.back()].empty() || children[ids.front()].size() < 2) continue;
      int inside = 0;
      for (size_t k = 1; k < ids.size(); ++k) {
        const Eigen::Vector3d& p = current.nodes[ids[k]].position;
        index.Nearest(p, 12, near, d2);
        for (size_t m = 0; m < near.size(); ++m) {
          const int other = near[m];
          if (chain_of[other] == static_cast<int>(c) || other == ids.front()) continue;
          if (std::sqrt(d2[m]) < current.nodes[other].radius) {
            ++inside;
            break;
          }
        }
      }
      if (inside > inside_share * (ids.size() - 1)) {
        for (size_t k = 1; k < ids.size(); ++k) remove[ids[k]] = 1;
        ++removed;
        s.nodes_removed += static_cast<int>(ids.size()) - 1;
      }
    }
    if (removed == 0) break;
    s.twigs_removed += removed;
    current = current.Without(remove);
  }
  return current;
}

}  // namespace simtree::reconstruction
