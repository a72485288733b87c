#include "simtree/io/detail/time_association.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace simtree::io_detail {

std::vector<std::pair<size_t, size_t>> AssociateByTime(const std::vector<double>& a,
                                                       const std::vector<double>& b,
                                                       double tolerance) {
  // Every pair within the tolerance (the streams are sorted, so a window per frame of a).
  std::vector<std::tuple<double, size_t, size_t>> candidates;
  for (size_t i = 0; i < a.size(); ++i) {
    auto j = std::lower_bound(b.begin(), b.end(), a[i] - tolerance);
    for (; j != b.end() && *j <= a[i] + tolerance; ++j) {
      candidates.emplace_back(std::abs(*j - a[i]), i, static_cast<size_t>(j - b.begin()));
    }
  }
  std::sort(candidates.begin(), candidates.end());
  std::vector<bool> used_a(a.size(), false), used_b(b.size(), false);
  std::vector<std::pair<size_t, size_t>> pairs;
  for (const auto& [distance, i, j] : candidates) {
    if (used_a[i] || used_b[j]) continue;
    used_a[i] = used_b[j] = true;
    pairs.emplace_back(i, j);
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace simtree::io_detail
