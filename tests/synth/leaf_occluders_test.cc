// Leaves swinging in front of markers (--hard): they cross the marker they were planned on,
// start clear of it, and painting one hides the tape in colour, depth and labels.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "simtree/core/error.h"
#include "simtree/synth/detail/leaf_occluders.h"
#include "test_util.h"

namespace simtree::synth {
namespace {

MarkerFrame2d OneMarker(double x, double y) {
  MarkerFrame2d frame;
  MarkerBox2d m;
  m.id = 4;
  m.visible = true;
  m.box = {x - 3, y - 3, 6, 6};
  frame.markers = {m};
  return frame;
}

TEST(LeafOccluders, EachLeafStartsClearOfItsMarkerAndLaterCrossesIt) {
  const Eigen::Vector2d marker(200, 150);
  const std::vector<LeafOccluder> leaves =
      PlanLeafOccluders(OneMarker(marker.x(), marker.y()), {.count = 3, .seed = 5});
  ASSERT_EQ(leaves.size(), 3u);
  for (const LeafOccluder& leaf : leaves) {
    EXPECT_GT((leaf.CentreAt(0.0) - marker).norm(), leaf.half_length_px + 4.0);
    double nearest = 1e9;
    for (double t = 0; t < 2 * leaf.period_s; t += 0.01) {
      nearest = std::min(nearest, (leaf.CentreAt(t) - marker).norm());
    }
    EXPECT_LT(nearest, 1.0);
  }
  EXPECT_TRUE(PlanLeafOccluders(MarkerFrame2d{}, {.seed = 1}).empty());
}

// At another image size (a colour camera of its own) the leaves keep their angular size: every
// length in pixels scales, the rest of the plan does not.
TEST(LeafOccluders, PixelScaleScalesEveryLengthInPixels) {
  const std::vector<LeafOccluder> base = PlanLeafOccluders(OneMarker(200, 150), {.seed = 5});
  const std::vector<LeafOccluder> wide =
      PlanLeafOccluders(OneMarker(300, 225), {.seed = 5, .pixel_scale = 1.5});
  ASSERT_EQ(base.size(), wide.size());
  for (size_t i = 0; i < base.size(); ++i) {
    EXPECT_DOUBLE_EQ(wide[i].amplitude_px, 1.5 * base[i].amplitude_px);
    EXPECT_DOUBLE_EQ(wide[i].half_length_px, 1.5 * base[i].half_length_px);
    EXPECT_NEAR((wide[i].centre - Eigen::Vector2d(300, 225)).norm(),
                1.5 * (base[i].centre - Eigen::Vector2d(200, 150)).norm(), 1e-9);
    EXPECT_EQ(wide[i].period_s, base[i].period_s);
    EXPECT_EQ(wide[i].depth_m, base[i].depth_m);
  }
  EXPECT_THROW(PlanLeafOccluders(OneMarker(200, 150), {.pixel_scale = 0.0}), InputError);
}

TEST(LeafOccluders, APaintedLeafHidesTheTapeInEveryImage) {
  RgbImage color(64, 48, 200);
  DepthImage depth(64, 48, 2500);
  LabelImage labels(64, 48);
  for (PixelLabel& l : labels.pixels) {
    l.kind = SurfaceKind::kBranch;
    l.marker = 4;
  }
  LeafOccluder leaf;
  leaf.centre = Eigen::Vector2d(30, 20);
  leaf.amplitude_px = 0.0;
  leaf.half_length_px = 8.0;
  leaf.half_width_px = 4.0;
  leaf.depth_m = 0.9;
  DrawLeafOccluders({leaf}, 0.0, color, depth, labels);
  EXPECT_EQ(labels.at(30, 20).marker, -1);
  EXPECT_EQ(labels.at(30, 20).kind, SurfaceKind::kOccluder);
  EXPECT_EQ(depth.at(30, 20), 900);
  EXPECT_LT(color.at(30, 20, 0), 100);
  EXPECT_EQ(labels.at(5, 5).marker, 4);  // outside the leaf: untouched
  EXPECT_EQ(depth.at(5, 5), 2500);
  int covered = 0;
  for (const PixelLabel& l : labels.pixels) covered += l.marker == -1;
  EXPECT_NEAR(covered, std::numbers::pi * 8 * 4, 12);

  DepthImage small(10, 10);
  EXPECT_THAT(test::ErrorOf([&] { DrawLeafOccluders({leaf}, 0.0, color, small, labels); }),
              ::testing::HasSubstr("one size"));
}

}  // namespace
}  // namespace simtree::synth
