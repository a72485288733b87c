#include "simtree/core/statistics.h"

#include <algorithm>

namespace simtree {

double Median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  if (values.size() % 2 == 1) return *middle;
  // Even count: the lower middle is the largest value before `middle`.
  return 0.5 * (*middle + *std::max_element(values.begin(), middle));
}

double UpperMedian(std::vector<double> values, double if_empty) {
  if (values.empty()) return if_empty;
  const auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace simtree
