#include "simtree/preprocessing/detail/option_checks.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace simtree::preprocessing {
namespace {

TEST(OptionChecks, ANonsenseValueNamesItsFieldAndWhatWasExpected) {
  try {
    CheckAtLeast("iterations", -3, 1);
    FAIL() << "-3 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "options");
    EXPECT_EQ(e.where(), "iterations");
    EXPECT_STREQ(e.what(), "options: iterations: expected >= 1, got -3");
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(CheckPositive("size_m", 0.0), OptionError);
  EXPECT_THROW(CheckPositive("size_m", nan), OptionError);
  EXPECT_THROW(CheckNonNegative("size_m", -1e-9), OptionError);
  EXPECT_THROW(CheckShare("share", 1.01), OptionError);
  EXPECT_THROW(CheckShare("share", nan), OptionError);
  EXPECT_THROW(CheckOrdered("min_m", 2.0, "max_m", 1.0), OptionError);
  EXPECT_NO_THROW(CheckPositive("size_m", 1e-9));
  EXPECT_NO_THROW(CheckShare("share", 0.0));
  EXPECT_NO_THROW(CheckOrdered("min_m", 1.0, "max_m", 1.0));
}

TEST(OptionChecks, ListsNameTheElementAndNestedStructsTheirMember) {
  try {
    CheckNested("pair", [] {
      CheckNested("icp", [] { CheckPositiveList("max_distances_m", {0.06, -0.03}, false); });
    });
    FAIL() << "a negative distance accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "pair.icp.max_distances_m[1]");
  }
  EXPECT_THROW(CheckPositiveList("factors", {}, false), OptionError);
  EXPECT_NO_THROW(CheckPositiveList("factors", {}, true));
}

}  // namespace
}  // namespace simtree::preprocessing
