#include "simtree/io/depth_colormap.h"

#include <gtest/gtest.h>

namespace simtree {
namespace {

TEST(DepthColormap, NoMeasurementIsBlackAndNearDiffersFromFar) {
  DepthImage depth(3, 1);
  depth.at(0, 0) = 0;
  depth.at(1, 0) = 600;   // near
  depth.at(2, 0) = 3800;  // far
  const RgbImage rgb = ColorizeDepth(depth);
  ASSERT_EQ(rgb.width, 3);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(rgb.at(0, 0, c), 0);
  // Near is warm (red above blue), far is cool (blue above red).
  EXPECT_GT(rgb.at(1, 0, 0), rgb.at(1, 0, 2));
  EXPECT_GT(rgb.at(2, 0, 2), rgb.at(2, 0, 0));
}

TEST(DepthColormap, OutOfRangeDepthsClampToTheEnds) {
  DepthImage depth(2, 1);
  depth.at(0, 0) = 100;  // nearer than near_m
  depth.at(1, 0) = 500;  // exactly near_m
  const RgbImage rgb = ColorizeDepth(depth);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(rgb.at(0, 0, c), rgb.at(1, 0, c));
}

}  // namespace
}  // namespace simtree
