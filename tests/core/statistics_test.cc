#include "simtree/core/statistics.h"

#include <cmath>

#include <gtest/gtest.h>

namespace simtree {
namespace {

TEST(Median, OddCountIsTheMiddleValue) { EXPECT_EQ(Median({5.0, 1.0, 3.0}), 3.0); }

TEST(Median, EvenCountIsTheMeanOfTheTwoMiddleValues) {
  EXPECT_EQ(Median({4.0, 1.0, 3.0, 10.0}), 3.5);
}

TEST(Median, EmptyIsNaN) { EXPECT_TRUE(std::isnan(Median({}))); }

TEST(UpperMedian, EvenCountIsTheUpperMiddleValue) {
  EXPECT_EQ(UpperMedian({4.0, 1.0, 3.0, 10.0}), 4.0);
  EXPECT_EQ(UpperMedian({5.0, 1.0, 3.0}), 3.0);
}

TEST(UpperMedian, EmptyGivesTheCallersValue) {
  EXPECT_TRUE(std::isnan(UpperMedian({})));
  EXPECT_EQ(UpperMedian({}, 0.0), 0.0);
}

}  // namespace
}  // namespace simtree
