#include "simtree/reconstruction/detail/skeleton_smoothing.h"

#include <vector>

#include "simtree/core/option_checks.h"

namespace simtree::reconstruction {

void SkeletonSmoothingOptions::Validate() const {
  CheckAtLeast("iterations", iterations, 0);
  CheckShare("weight", weight);
  CheckInRange("inflate", inflate, 0.0, 1.0);
}

void SmoothSkeleton(Skeleton& skeleton, const SkeletonSmoothingOptions& options) {
  options.Validate();
  if (options.iterations <= 0 || skeleton.size() < 3) return;
  const std::vector<SkeletonChain> chains = SkeletonChains(skeleton);
  std::vector<Eigen::Vector3d> next;
  auto step = [&](double factor) {
    for (const SkeletonChain& chain : chains) {
      const auto& ids = chain.nodes;
      if (ids.size() < 3) continue;
      next.resize(ids.size());
      for (size_t k = 1; k + 1 < ids.size(); ++k) {
        const Eigen::Vector3d& p = skeleton.nodes[ids[k]].position;
        const Eigen::Vector3d mean =
            0.5 * (skeleton.nodes[ids[k - 1]].position + skeleton.nodes[ids[k + 1]].position);
        next[k] = p + factor * (mean - p);
      }
      for (size_t k = 1; k + 1 < ids.size(); ++k) skeleton.nodes[ids[k]].position = next[k];
    }
  };
  for (int it = 0; it < options.iterations; ++it) {
    step(options.weight);
    if (options.inflate > 0) step(-options.inflate);
  }
}

}  // namespace simtree::reconstruction
