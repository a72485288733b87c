#pragma once
// Where a reconstruction misses a real scan's points by 2-10 cm, and what a reference skeleton
// (AdTree's) has at the same places: the diagnosis behind docs/reconstruction.md's "Limits".

#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "simtree/core/tree.h"

namespace simtree::bench {

// Prints, for the points 2-10 cm from `ours`, a table by the radius of the nearest model branch:
// inside or outside the wood, whether the reference fits them (within 2 cm), whether the
// reference's axis there lies outside our wood (a branch we lack) or inside it with a thicker
// radius, and how many form a separate twig (an elongated cluster leaving the branch) rather than
// a shell around it. `link_m` joins missed points into clusters.
// Where the reference has wood we lack, whether our pipeline had it at some stage: the skeleton as
// grown (before pruning and smoothing; its edges sampled densely) within `grown_near_m` of the
// reference's axis, else an attraction point (medial sample) within `sample_near_m`.
struct Stages {
  std::vector<Eigen::Vector3d> samples, grown;
  double grown_near_m = 0.0, sample_near_m = 0.0;
};

void PrintMisses(const std::string& name, const Tree& ours, const Tree& reference,
                 std::span<const Eigen::Vector3d> points, double link_m, const Stages& stages);

}  // namespace simtree::bench
