#include "simtree/preprocessing/point_spacing.h"

#include <gtest/gtest.h>

#include "preprocessing/option_fixtures.h"

namespace simtree::preprocessing {
namespace {

TEST(PointSpacing, GridSpacingIsMeasured) {
  open3d::geometry::PointCloud cloud;
  for (int i = 0; i < 100; ++i) {
    for (int j = 0; j < 100; ++j) cloud.points_.emplace_back(0.007 * i, 0.007 * j, 1.0);
  }
  EXPECT_NEAR(MedianPointSpacing(cloud), 0.007, 1e-9);
}

TEST(PointSpacing, DuplicatesAndTinyCloudsDoNotBreakIt) {
  open3d::geometry::PointCloud cloud;
  EXPECT_EQ(MedianPointSpacing(cloud), 0.0);
  cloud.points_ = {Eigen::Vector3d(0, 0, 0)};
  EXPECT_EQ(MedianPointSpacing(cloud), 0.0);
  for (int i = 0; i < 50; ++i) {
    cloud.points_.emplace_back(0.01 * i, 0, 0);
    cloud.points_.emplace_back(0.01 * i, 0, 0);  // every point twice
  }
  EXPECT_NEAR(MedianPointSpacing(cloud), 0.01, 1e-9);
}

TEST(PointSpacing, NonsenseOptionsAreRefused) {
  EXPECT_EQ(test::RefusedField(SpacingOptions{}), "");
  EXPECT_EQ(test::RefusedField(SpacingOptions{.max_samples = 0}), "max_samples");
  // The nearest neighbour of a point is itself: one neighbour measures nothing.
  EXPECT_EQ(test::RefusedField(SpacingOptions{.neighbours = 1}), "neighbours");
}

}  // namespace
}  // namespace simtree::preprocessing
