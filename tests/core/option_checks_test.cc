#include "simtree/core/option_checks.h"

#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "test_util.h"

namespace simtree {
namespace {

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// The message of the OptionError a check throws, "" when it passes.
template <typename Check>
std::string MessageOf(Check check) {
  return test::ErrorOf<OptionError>(check);
}

struct Inner {
  int count = 1;
  void Validate() const { CheckAtLeast("count", count, 1); }
};
struct Outer {
  Inner inner;
  void Validate() const { CheckNested("inner", inner); }
};

TEST(OptionChecks, NameTheFieldAndWhatWasExpected) {
  try {
    CheckPositive("step_m", -3.0);
    FAIL() << "no throw";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "options");
    EXPECT_EQ(e.where(), "step_m");
    EXPECT_STREQ(e.what(), "options: step_m: expected > 0, got -3");
  }
  EXPECT_EQ(MessageOf([] { CheckNonNegative("gap_m", -0.5); }),
            "options: gap_m: expected >= 0, got -0.5");
  EXPECT_EQ(MessageOf([] { CheckAtLeast("iterations", -3, 1); }),
            "options: iterations: expected >= 1, got -3");
  EXPECT_EQ(MessageOf([] { CheckAtLeast("ratio", 0.5, 1.0); }),
            "options: ratio: expected >= 1, got 0.5");
  EXPECT_EQ(MessageOf([] { CheckInRange("min_radius_m", -2.0, 0.0, 1.0); }),
            "options: min_radius_m: expected a value in [0, 1], got -2");
  EXPECT_EQ(MessageOf([] { CheckShare("share", 1.5); }),
            "options: share: expected a value in [0, 1], got 1.5");
  EXPECT_EQ(MessageOf([] { CheckOrdered("min_m", 2.0, "max_m", 1.0); }),
            "options: max_m: expected >= min_m (2), got 1");
  EXPECT_EQ(MessageOf([] { CheckThat(false, "mode", "0, 1 or 2", 3); }),
            "options: mode: expected 0, 1 or 2, got 3");
}

TEST(OptionChecks, CheckOptionKeepsItsSourceThroughNesting) {
  const auto check = [] { CheckOption(false, "wind options", "seed", "expected a seed"); };
  EXPECT_EQ(MessageOf(check), "wind options: seed: expected a seed");
  EXPECT_EQ(MessageOf([&] { CheckNested("wind", check); }),
            "wind options: wind.seed: expected a seed");
  EXPECT_EQ(MessageOf([] { CheckOption(true, "wind options", "seed", "unused"); }), "");
}

TEST(OptionChecks, NestedStructsAndListsNameTheMemberAndElement) {
  EXPECT_EQ(MessageOf([] { Outer{.inner = {.count = 0}}.Validate(); }),
            "options: inner.count: expected >= 1, got 0");
  EXPECT_EQ(MessageOf([] { Outer{}.Validate(); }), "");
  try {
    CheckNested("pair", [] {
      CheckNested("icp", [] { CheckPositiveList("max_distances_m", {0.06, -0.03}, false); });
    });
    FAIL() << "a negative distance accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "pair.icp.max_distances_m[1]");
    EXPECT_EQ(e.expected(), "expected > 0, got -0.03");
  }
  EXPECT_THROW(CheckPositiveList("factors", {}, false), OptionError);
  EXPECT_NO_THROW(CheckPositiveList("factors", {}, true));
}

TEST(OptionChecks, NanAndInfinityFail) {
  EXPECT_THROW(CheckPositive("x", kNan), OptionError);
  EXPECT_THROW(CheckPositive("x", kInf), OptionError);
  EXPECT_THROW(CheckNonNegative("x", kNan), OptionError);
  EXPECT_THROW(CheckNonNegative("x", kInf), OptionError);
  EXPECT_THROW(CheckAtLeast("x", kNan, 1.0), OptionError);
  EXPECT_THROW(CheckAtLeast("x", kInf, 1.0), OptionError);
  EXPECT_THROW(CheckShare("x", kNan), OptionError);
  EXPECT_THROW(CheckInRange("x", kNan, -kInf, kInf), OptionError);
  EXPECT_THROW(CheckOrdered("lo", 1.0, "hi", kNan), OptionError);
  EXPECT_THROW(CheckOrdered("lo", 1.0, "hi", kInf), OptionError);
}

TEST(OptionChecks, BoundsAreIncluded) {
  EXPECT_NO_THROW(CheckPositive("x", 1e-9));
  EXPECT_THROW(CheckPositive("x", 0.0), OptionError);
  EXPECT_NO_THROW(CheckNonNegative("x", 0.0));
  EXPECT_THROW(CheckNonNegative("x", -1e-9), OptionError);
  EXPECT_NO_THROW(CheckAtLeast("x", 1, 1));
  EXPECT_THROW(CheckAtLeast("x", int64_t{0}, 1), OptionError);
  EXPECT_NO_THROW(CheckShare("x", 0.0));
  EXPECT_NO_THROW(CheckShare("x", 1.0));
  EXPECT_THROW(CheckShare("x", 1.01), OptionError);
  EXPECT_NO_THROW(CheckOrdered("lo", 1.0, "hi", 1.0));
}

}  // namespace
}  // namespace simtree
