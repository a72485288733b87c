#pragma once
// Minimum-cost assignment of rows to columns (the Hungarian method, shortest augmenting paths
// with potentials, O(n^2 m)): which detection belongs to which marker prediction.

#include <vector>

namespace simtree::tracking::detail {

// `cost` is rows x cols (row-major, every row the same length); entries >= `forbidden` may not be
// assigned. Returns for every row the column assigned to it, or -1 (more rows than columns, or
// only forbidden entries left). Minimises the sum of assigned costs over the assignments that
// assign as many rows as possible.
std::vector<int> SolveAssignment(const std::vector<std::vector<double>>& cost, double forbidden);

}  // namespace simtree::tracking::detail
