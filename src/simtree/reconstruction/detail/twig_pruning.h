#pragma once
// Pruning of twigs the scan does not support. Space colonization grows a twig towards any point
// it perceives, so stray points, noise on thick wood and the far side of an occlusion leave short
// or nearly empty twigs. A twig (a chain from a fork to a tip) is removed when it explains too
// few scan points, in all or per metre (a twig grown through sensor noise is much sparser than the
// wood around it), or when it is shorter than the wood it grows from is thick (a bump on a trunk,
// not a branch).

#include "simtree/reconstruction/detail/skeleton.h"

namespace simtree::reconstruction {

struct TwigPruningOptions {
  double min_support = 6.0;               // scan points a twig must explain...
  double min_support_per_m = 0.0;         // ... and this many per metre of its length (0: off)
  double min_length_m = 0.0;              // metres: shorter twigs are removed
  double min_length_per_thickness = 1.5;  // x the thickness where the twig starts; 0: off
  int passes = 3;                         // pruning can expose new twigs; repeat this often

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

struct TwigPruningStats {
  int twigs_removed = 0;
  int nodes_removed = 0;

  TwigPruningStats operator+(const TwigPruningStats& other) const {
    return {twigs_removed + other.twigs_removed, nodes_removed + other.nodes_removed};
  }
};

Skeleton PruneTwigs(const Skeleton& skeleton, const TwigPruningOptions& options,
                    TwigPruningStats* stats = nullptr);

// Once radii are known: removes twigs that run mostly inside other wood (more than `inside_share`
// of their nodes within the radius of the nearest node of another chain). Arcs of a thick branch
// that occlusion split off grow such twigs along the inside of its bark.
Skeleton PruneTwigsInsideWood(const Skeleton& skeleton, double inside_share = 0.6, int passes = 3,
                              TwigPruningStats* stats = nullptr);

}  // namespace simtree::reconstruction
