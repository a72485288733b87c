#pragma once
// Order statistics shared by the stages (one definition instead of a copy in every unit).

#include <limits>
#include <vector>

namespace simtree {

// The median: the middle value, or the mean of the two middle values for an even count; NaN when
// `values` is empty.
double Median(std::vector<double> values);

// The upper median: the value at index size/2 once sorted, never an average (one nth_element,
// and always a value that occurs); `if_empty` when `values` is empty.
double UpperMedian(std::vector<double> values,
                   double if_empty = std::numeric_limits<double>::quiet_NaN());

}  // namespace simtree
