// The option checks, and the Validate() of the options structs ReconstructTree derives rather
// than takes (the others are tested through ReconstructionOptions in reconstruct_test.cc).

#include "simtree/reconstruction/detail/option_checks.h"

#include <limits>

#include <gtest/gtest.h>

#include "simtree/reconstruction/detail/cloud_scale.h"
#include "simtree/reconstruction/detail/geodesic_samples.h"
#include "simtree/reconstruction/detail/scan_graph.h"
#include "simtree/reconstruction/detail/scene_cleanup.h"
#include "simtree/reconstruction/detail/space_colonization.h"
#include "simtree/reconstruction/reconstruction_plot.h"

namespace simtree::reconstruction {
namespace {

template <typename Options>
std::string MessageOf(const Options& options) {
  try {
    options.Validate();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
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
  EXPECT_EQ(MessageOf(Outer{.inner = {.count = 0}}), "options: inner.count: expected >= 1, got 0");
  EXPECT_EQ(MessageOf(Outer{}), "");
}

TEST(OptionChecks, NanAndInfinityFail) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(CheckPositive("x", nan), OptionError);
  EXPECT_THROW(CheckPositive("x", inf), OptionError);
  EXPECT_THROW(CheckNonNegative("x", nan), OptionError);
  EXPECT_THROW(CheckShare("x", nan), OptionError);
  EXPECT_THROW(CheckNotBelow("x", nan, 1.0), OptionError);
  EXPECT_THROW(CheckOrdered("lo", 1.0, "hi", nan), OptionError);
  EXPECT_NO_THROW(CheckNotBelow("x", inf, 1.0));
  EXPECT_NO_THROW(CheckShare("x", 1.0));
}

TEST(OptionChecks, DerivedOptionsRefuseNonsense) {
  EXPECT_EQ(MessageOf(CloudScaleOptions{.samples = 0}), "options: samples: expected >= 1, got 0");
  EXPECT_EQ(MessageOf(ScanGraphOptions{.neighbour_radius_m = 0.0}),
            "options: neighbour_radius_m: expected > 0, got 0");
  EXPECT_EQ(MessageOf(GeodesicSampleOptions{.band_width_m = -0.02}),
            "options: band_width_m: expected > 0, got -0.02");
  EXPECT_EQ(MessageOf(SparseReturnOptions{.min_neighbours = -1}),
            "options: min_neighbours: expected >= 0, got -1");
  EXPECT_EQ(MessageOf(GroundObjectOptions{.touch_height_m = -0.05}),
            "options: touch_height_m: expected >= 0, got -0.05");
  EXPECT_EQ(MessageOf(ColonizationLengths{.kill_radius_m = 0.0}),
            "options: kill_radius_m: expected > 0, got 0");
  ReconstructionPlotOptions plot;
  plot.model_opacity = 1.5;
  EXPECT_EQ(MessageOf(plot), "options: model_opacity: expected within [0, 1], got 1.5");
  for (const std::string& m : {MessageOf(CloudScaleOptions{}), MessageOf(ScanGraphOptions{}),
                               MessageOf(GeodesicSampleOptions{}), MessageOf(SparseReturnOptions{}),
                               MessageOf(GroundObjectOptions{}), MessageOf(ColonizationLengths{}),
                               MessageOf(ReconstructionPlotOptions{})}) {
    EXPECT_EQ(m, "") << "defaults are valid";
  }
}

}  // namespace
}  // namespace simtree::reconstruction
