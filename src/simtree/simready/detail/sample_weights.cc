#include "simtree/simready/detail/sample_weights.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "simtree/core/statistics.h"
#include "simtree/core/units.h"

namespace simtree::simready {

std::vector<double> InverseVarianceWeights(const std::vector<double>& values,
                                           const std::vector<double>& stds) {
  std::vector<double> relative(values.size(), kNaN), given;
  for (size_t i = 0; i < values.size(); ++i) {
    if (std::isnan(stds[i])) continue;
    relative[i] = std::abs(stds[i] / values[i]);
    if (std::isfinite(relative[i])) given.push_back(relative[i]);
  }
  std::vector<double> weights(values.size(), 1.0);
  if (given.empty()) return weights;
  const double floor = Median(given);
  const double least_certain = *std::max_element(given.begin(), given.end());
  if (!(floor > 0)) return weights;  // every deviation zero: nothing to tell the values apart
  for (size_t i = 0; i < values.size(); ++i) {
    double s = relative[i];
    if (std::isnan(s)) s = floor;
    if (std::isinf(s)) s = least_certain;
    s = std::max(s, floor);
    weights[i] = (floor * floor) / (s * s);  // the floor's weight is 1, the largest
  }
  return weights;
}

double WeightedMedian(const std::vector<double>& values, const std::vector<double>& weights) {
  if (values.empty()) return kNaN;
  std::vector<size_t> order(values.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return values[a] < values[b]; });
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  const double half = 0.5 * total;
  double cumulative = 0.0;
  for (size_t k = 0; k < order.size(); ++k) {
    cumulative += weights[order[k]];
    if (cumulative < half - 1e-12 * total) continue;
    // Exactly at the half (up to rounding): the half falls between this value and the next.
    if (std::abs(cumulative - half) <= 1e-12 * total && k + 1 < order.size()) {
      return 0.5 * (values[order[k]] + values[order[k + 1]]);
    }
    return values[order[k]];
  }
  return values[order.back()];
}

}  // namespace simtree::simready
