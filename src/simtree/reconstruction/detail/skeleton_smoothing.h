#pragma once
// Smoothing of a grown skeleton: space colonization steps towards noisy attraction points, so its
// chains zigzag by about the noise. A few rounds of smoothing along each chain (forks, tips and
// the root stay put) straighten them without moving the forks. Each round is Taubin's pair of
// steps: a Laplacian step that removes the zigzag, then a slightly larger step back that undoes
// its shrinking of gentle bends (plain Laplacian smoothing pulls a curved branch towards its
// chord, off the wood the points show, and shortens it).

#include "simtree/reconstruction/detail/skeleton.h"

namespace simtree::reconstruction {

struct SkeletonSmoothingOptions {
  int iterations = 2;   // rounds (0: off)
  double weight = 0.5;  // share of the way to the mean of its two neighbours a node moves a round
  // Share of the way back a node moves after each such step (Taubin's -mu; 0: plain Laplacian).
  // A little above `weight`: zigzags still go, gentle bends keep their shape.
  double inflate = 0.53;

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

void SmoothSkeleton(Skeleton& skeleton, const SkeletonSmoothingOptions& options);

}  // namespace simtree::reconstruction
