#include "simtree/preprocessing/point_spacing.h"

#include <algorithm>
#include <random>

#include <open3d/geometry/KDTreeFlann.h>

#include "simtree/core/option_checks.h"

namespace simtree::preprocessing {

void SpacingOptions::Validate() const {
  CheckPositive("max_samples", static_cast<double>(max_samples));
  CheckAtLeast("neighbours", neighbours, 2);
}

double MedianPointSpacing(const open3d::geometry::PointCloud& cloud,
                          const SpacingOptions& options) {
  options.Validate();
  const size_t n = cloud.points_.size();
  if (n < 2) return 0.0;
  std::vector<size_t> sample(n);
  for (size_t i = 0; i < n; ++i) sample[i] = i;
  if (n > options.max_samples) {
    std::mt19937_64 rng(options.seed);
    std::shuffle(sample.begin(), sample.end(), rng);
    sample.resize(options.max_samples);
  }
  open3d::geometry::KDTreeFlann tree(cloud);
  std::vector<double> distances;
  distances.reserve(sample.size());
  std::vector<int> indices;
  std::vector<double> squared;
  for (size_t i : sample) {
    tree.SearchKNN(cloud.points_[i], options.neighbours, indices, squared);
    // Exact duplicates (a point written twice) say nothing about the sampling density: the
    // nearest neighbour at a distance above zero does.
    const auto next = std::find_if(squared.begin(), squared.end(), [](double d) { return d > 0; });
    if (next != squared.end()) distances.push_back(std::sqrt(*next));
  }
  if (distances.empty()) return 0.0;
  auto middle = distances.begin() + distances.size() / 2;
  std::nth_element(distances.begin(), middle, distances.end());
  return *middle;
}

}  // namespace simtree::preprocessing
