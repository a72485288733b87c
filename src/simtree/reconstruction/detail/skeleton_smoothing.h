#pragma once
// Smoothing of a grown skeleton: space colonization steps towards noisy attraction points, so its
// chains zigzag by about the noise. A few rounds of Laplacian smoothing along each chain (forks,
// tips and the root stay put) straighten them without moving the forks.

#include "simtree/reconstruction/detail/skeleton.h"

namespace simtree::reconstruction {

struct SkeletonSmoothingOptions {
  int iterations = 2;   // rounds (0: off)
  double weight = 0.5;  // share of the way to the mean of its two neighbours a node moves a round

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

void SmoothSkeleton(Skeleton& skeleton, const SkeletonSmoothingOptions& options);

}  // namespace simtree::reconstruction
