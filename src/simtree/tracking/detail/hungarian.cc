#include "simtree/tracking/detail/hungarian.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace simtree::tracking::detail {
namespace {

// Jonker-Volgenant style shortest augmenting path on a square matrix `a` (n x n, 1-based
// potentials). Returns the column of every row.
std::vector<int> SolveSquare(const std::vector<std::vector<double>>& a) {
  const int n = static_cast<int>(a.size());
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0.0), v(n + 1, 0.0);
  std::vector<int> match(n + 1, 0), way(n + 1, 0);  // match[col] = row (1-based), 0 = free
  for (int row = 1; row <= n; ++row) {
    match[0] = row;
    int col0 = 0;
    std::vector<double> min_to(n + 1, inf);
    std::vector<bool> used(n + 1, false);
    do {
      used[col0] = true;
      const int row0 = match[col0];
      double delta = inf;
      int col1 = 0;
      for (int col = 1; col <= n; ++col) {
        if (used[col]) continue;
        const double reduced = a[row0 - 1][col - 1] - u[row0] - v[col];
        if (reduced < min_to[col]) {
          min_to[col] = reduced;
          way[col] = col0;
        }
        if (min_to[col] < delta) {
          delta = min_to[col];
          col1 = col;
        }
      }
      for (int col = 0; col <= n; ++col) {
        if (used[col]) {
          u[match[col]] += delta;
          v[col] -= delta;
        } else {
          min_to[col] -= delta;
        }
      }
      col0 = col1;
    } while (match[col0] != 0);
    do {
      const int col1 = way[col0];
      match[col0] = match[col1];
      col0 = col1;
    } while (col0 != 0);
  }
  std::vector<int> row_to_col(n, -1);
  for (int col = 1; col <= n; ++col) {
    if (match[col] > 0) row_to_col[match[col] - 1] = col - 1;
  }
  return row_to_col;
}

}  // namespace

std::vector<int> SolveAssignment(const std::vector<std::vector<double>>& cost, double forbidden) {
  const int rows = static_cast<int>(cost.size());
  if (rows == 0) return {};
  const int cols = static_cast<int>(cost[0].size());
  // Square it: padding entries and forbidden pairs cost `big`, more than any set of allowed
  // pairs, so the solver first maximises the number of allowed pairs, then minimises their cost.
  double allowed_sum = 0.0;
  for (const auto& row : cost) {
    for (double c : row) {
      if (c < forbidden) allowed_sum += std::abs(c);
    }
  }
  const double big = 2.0 * allowed_sum + 1.0;
  const int n = std::max(rows, cols);
  std::vector<std::vector<double>> square(n, std::vector<double>(n, big));
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (cost[r][c] < forbidden) square[r][c] = cost[r][c];
    }
  }
  const std::vector<int> assigned = SolveSquare(square);
  std::vector<int> out(rows, -1);
  for (int r = 0; r < rows; ++r) {
    const int c = assigned[r];
    if (c >= 0 && c < cols && cost[r][c] < forbidden) out[r] = c;
  }
  return out;
}

}  // namespace simtree::tracking::detail
