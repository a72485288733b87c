#include "simtree/reconstruction/detail/cloud_scale.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include "simtree/core/option_checks.h"
#include "simtree/core/statistics.h"
#include "simtree/reconstruction/detail/local_geometry.h"
#include "simtree/reconstruction/detail/point_index.h"

namespace simtree::reconstruction {

void CloudScaleOptions::Validate() const {
  CheckAtLeast("samples", samples, 1);
  CheckAtLeast("max_indexed_points", static_cast<int64_t>(max_indexed_points), 3);
  CheckAtLeast("noise_neighbours", noise_neighbours, 3);
}

CloudScale MeasureCloudScale(std::span<const Eigen::Vector3d> all_points,
                             const CloudScaleOptions& options) {
  options.Validate();
  CloudScale scale;
  if (all_points.size() < 3) return scale;
  std::mt19937_64 rng(options.seed);
  // A random subset of `count` indices of [0, n) (the first `count` of a partial shuffle).
  auto subset = [&](size_t n, size_t count) {
    std::vector<int> ids(n);
    for (size_t i = 0; i < n; ++i) ids[i] = static_cast<int>(i);
    for (size_t i = 0; i < std::min(count, n); ++i) {
      std::uniform_int_distribution<size_t> pick(i, n - 1);
      std::swap(ids[i], ids[pick(rng)]);
    }
    ids.resize(std::min(count, n));
    return ids;
  };
  std::vector<Eigen::Vector3d> thinned;
  std::span<const Eigen::Vector3d> points = all_points;
  double density_correction = 1.0;
  if (all_points.size() > options.max_indexed_points) {
    for (const int i : subset(all_points.size(), options.max_indexed_points)) {
      thinned.push_back(all_points[i]);
    }
    points = thinned;
    density_correction =
        std::sqrt(static_cast<double>(thinned.size()) / static_cast<double>(all_points.size()));
  }
  const PointIndex index(points);
  const std::vector<int> sample = subset(points.size(), options.samples);
  std::vector<double> spacing, neighbourhood, roughness;
  spacing.reserve(sample.size());
  roughness.reserve(sample.size());
  std::vector<int> near;
  std::vector<double> d2;
  const int k = std::max(options.noise_neighbours, 4);
  for (const int i : sample) {
    index.Nearest(points[i], k + 1, near, d2);
    if (near.size() < 2) continue;
    spacing.push_back(std::sqrt(d2[1]));  // d2[0] is the point itself
    if (near.size() > 6) neighbourhood.push_back(std::sqrt(d2[6]));
    if (static_cast<int>(near.size()) < k) continue;
    Eigen::Vector3d mean;
    const Eigen::Matrix3d cov = NeighbourhoodCovariance(points, near, &mean);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov, Eigen::EigenvaluesOnly);
    roughness.push_back(std::sqrt(std::max(eig.eigenvalues()[0], 0.0)));
  }
  scale.spacing_m = UpperMedian(std::move(spacing), 0.0) * density_correction;
  scale.neighbourhood_m = UpperMedian(std::move(neighbourhood), 0.0) * density_correction;
  scale.roughness_m = UpperMedian(std::move(roughness), 0.0);
  return scale;
}

}  // namespace simtree::reconstruction
