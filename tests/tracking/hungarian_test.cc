#include "simtree/tracking/detail/hungarian.h"

#include <limits>

#include <gtest/gtest.h>

namespace simtree::tracking::detail {
namespace {

constexpr double kNo = std::numeric_limits<double>::infinity();

TEST(Hungarian, FindsTheCheapestSquareAssignment) {
  // Greedy (row 0 takes its cheapest, column 0) costs 1 + 9 = 10; the optimum is 2 + 3 = 5.
  const std::vector<std::vector<double>> cost = {{1, 2}, {3, 9}};
  EXPECT_EQ(SolveAssignment(cost, kNo), (std::vector<int>{1, 0}));
}

TEST(Hungarian, ThreeByThreeOptimum) {
  const std::vector<std::vector<double>> cost = {{4, 1, 3}, {2, 0, 5}, {3, 2, 2}};
  EXPECT_EQ(SolveAssignment(cost, kNo), (std::vector<int>{1, 0, 2}));  // 1 + 2 + 2
}

TEST(Hungarian, MoreRowsThanColumnsLeavesTheCostliestUnassigned) {
  const std::vector<std::vector<double>> cost = {{5}, {1}, {3}};
  EXPECT_EQ(SolveAssignment(cost, kNo), (std::vector<int>{-1, 0, -1}));
}

TEST(Hungarian, ForbiddenPairsAreNeverAssigned) {
  const std::vector<std::vector<double>> cost = {{kNo, 1}, {kNo, 2}};
  const std::vector<int> a = SolveAssignment(cost, kNo);
  EXPECT_EQ(a[0] + a[1], 0);  // one row gets column 1, the other nothing
  EXPECT_TRUE((a == std::vector<int>{1, -1}));
}

TEST(Hungarian, PrefersMoreAssignmentsOverCheaperOnes) {
  // Row 0 alone would take column 0 (cost 0); then row 1 (only column 0 allowed) gets nothing.
  const std::vector<std::vector<double>> cost = {{0, 0.9}, {0.5, kNo}};
  EXPECT_EQ(SolveAssignment(cost, kNo), (std::vector<int>{1, 0}));
}

TEST(Hungarian, EmptyInputs) {
  EXPECT_TRUE(SolveAssignment({}, kNo).empty());
  EXPECT_EQ(SolveAssignment({{}, {}}, kNo), (std::vector<int>{-1, -1}));
}

}  // namespace
}  // namespace simtree::tracking::detail
