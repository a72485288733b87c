#pragma once
// Pairs the frames of two streams by time (TUM RGB-D's colour and depth, a bag's colour and
// depth topics): each frame used at most once, the closest pairs first, none further apart than a
// tolerance.

#include <cstddef>
#include <utility>
#include <vector>

namespace simtree::io_detail {

// `a` and `b` increase. Returns (index in a, index in b) pairs with |a - b| <= tolerance, sorted
// by the index in a; ties in distance go to the earlier frames.
std::vector<std::pair<size_t, size_t>> AssociateByTime(const std::vector<double>& a,
                                                       const std::vector<double>& b,
                                                       double tolerance);

}  // namespace simtree::io_detail
