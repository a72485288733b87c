#include "simtree/preprocessing/depth_to_cloud.h"

#include <gtest/gtest.h>

#include "preprocessing/option_fixtures.h"
#include "simtree/core/error.h"

namespace simtree::preprocessing {
namespace {

RgbdImage Flat(int w, int h, uint16_t depth_mm) {
  RgbdImage image;
  image.intrinsics = {w, h, 100.0, 100.0, (w - 1) / 2.0, (h - 1) / 2.0, 0.001};
  image.depth = DepthImage(w, h, depth_mm);
  image.color = RgbImage(w, h, 50);
  return image;
}

TEST(DepthToCloud, UnprojectsEveryPixelWithItsDepth) {
  const RgbdImage image = Flat(9, 7, 2000);
  const auto cloud = DepthToCloud(image);
  ASSERT_EQ(cloud.points_.size(), 63u);
  ASSERT_EQ(cloud.colors_.size(), 63u);
  // Pixel (0, 0): x = (0 - 4) / 100 * 2, y = (0 - 3) / 100 * 2.
  EXPECT_NEAR(cloud.points_[0].x(), -0.08, 1e-12);
  EXPECT_NEAR(cloud.points_[0].y(), -0.06, 1e-12);
  EXPECT_NEAR(cloud.points_[0].z(), 2.0, 1e-12);
  EXPECT_NEAR(cloud.colors_[0].x(), 50 / 255.0, 1e-12);
}

TEST(DepthToCloud, SkipsMissingAndOutOfRangeDepths) {
  RgbdImage image = Flat(9, 7, 2000);
  image.depth.at(1, 1) = 0;     // no measurement
  image.depth.at(2, 2) = 100;   // 0.1 m: nearer than the range
  image.depth.at(3, 3) = 9000;  // 9 m: beyond it
  DepthToCloudOptions options;
  options.flying_min_jump_m = 0;  // keep isolated pixels
  EXPECT_EQ(DepthToCloud(image, options).points_.size(), 60u);
}

TEST(DepthToCloud, DropsFlyingPixelsBetweenSurfaces) {
  RgbdImage image = Flat(9, 7, 3000);
  for (int y = 0; y < 7; ++y) {
    for (int x = 0; x < 4; ++x) image.depth.at(x, y) = 1000;  // a near surface on the left
  }
  image.depth.at(4, 3) = 2000;  // an edge pixel halfway between the two surfaces
  const auto cloud = DepthToCloud(image);
  EXPECT_EQ(cloud.points_.size(), 62u);
  for (const auto& p : cloud.points_) EXPECT_NE(p.z(), 2.0);
}

TEST(DepthToCloud, AllZeroDepthGivesNoPoints) {
  EXPECT_TRUE(DepthToCloud(Flat(9, 7, 0)).points_.empty());
}

TEST(DepthToCloud, ImagesThatDoNotMatchTheIntrinsicsAreRefused) {
  RgbdImage image = Flat(9, 7, 2000);
  image.depth = DepthImage(8, 7, 2000);
  EXPECT_THROW(DepthToCloud(image, {}, "view_00"), InputError);
  image = Flat(9, 7, 2000);
  image.color = RgbImage(9, 6, 0);
  EXPECT_THROW(DepthToCloud(image, {}, "view_00"), InputError);
  image = Flat(9, 7, 2000);
  image.intrinsics.fx = 0;
  EXPECT_THROW(DepthToCloud(image, {}, "view_00"), InputError);
}

TEST(DepthToCloud, NonsenseOptionsAreRefused) {
  using Options = DepthToCloudOptions;
  EXPECT_EQ(test::RefusedField(Options{}), "");
  EXPECT_EQ(test::RefusedField(Options{.stride = 0}), "stride");
  EXPECT_EQ(test::RefusedField(Options{.min_depth_m = 7.0}), "max_depth_m");  // below the min
  EXPECT_EQ(test::RefusedField(Options{.flying_jump_share = -0.1}), "flying_jump_share");
  EXPECT_THROW(DepthToCloud(Flat(9, 7, 2000), Options{.stride = 0}), InputError);
}

}  // namespace
}  // namespace simtree::preprocessing
