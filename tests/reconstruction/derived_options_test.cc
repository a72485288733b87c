// The Validate() of the options structs ReconstructTree derives rather than takes (the others are
// tested through ReconstructionOptions in reconstruct_test.cc; the checks themselves in
// tests/core/option_checks_test.cc).

#include <string>

#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/reconstruction/detail/cloud_scale.h"
#include "simtree/reconstruction/detail/geodesic_samples.h"
#include "simtree/reconstruction/detail/scan_graph.h"
#include "simtree/reconstruction/detail/scene_cleanup.h"
#include "simtree/reconstruction/detail/space_colonization.h"
#include "simtree/reconstruction/reconstruction_plot.h"
#include "test_util.h"

namespace simtree::reconstruction {
namespace {

// What Validate() throws for `options`, "" when it accepts them.
template <typename Options>
std::string MessageOf(const Options& options) {
  return test::ErrorOf<InputError>([&] { options.Validate(); });
}

TEST(DerivedOptions, RefuseNonsense) {
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
  EXPECT_EQ(MessageOf(plot), "options: model_opacity: expected a value in [0, 1], got 1.5");
  for (const std::string& m : {MessageOf(CloudScaleOptions{}), MessageOf(ScanGraphOptions{}),
                               MessageOf(GeodesicSampleOptions{}), MessageOf(SparseReturnOptions{}),
                               MessageOf(GroundObjectOptions{}), MessageOf(ColonizationLengths{}),
                               MessageOf(ReconstructionPlotOptions{})}) {
    EXPECT_EQ(m, "") << "defaults are valid";
  }
}

}  // namespace
}  // namespace simtree::reconstruction
