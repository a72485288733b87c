#include "simtree/reconstruction/detail/voxel_grid.h"

#include <gtest/gtest.h>

namespace simtree::reconstruction {
namespace {

TEST(VoxelGrid, AveragesThePointsOfEachVoxel) {
  const std::vector<Eigen::Vector3d> points = {
      {0.01, 0.01, 0.01}, {0.03, 0.03, 0.03}, {0.15, 0.01, 0.01}, {0.01, 0.01, 0.01}};
  const auto out = VoxelAverage(points, 0.1);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_TRUE(out[0].isApprox(Eigen::Vector3d(0.05 / 3, 0.05 / 3, 0.05 / 3)));
  EXPECT_TRUE(out[1].isApprox(Eigen::Vector3d(0.15, 0.01, 0.01)));
  EXPECT_TRUE(VoxelAverage({}, 0.1).empty());
  EXPECT_TRUE(VoxelAverage(points, 0.0).empty());
}

TEST(VoxelGrid, CoarsensUntilAtMostTheLimit) {
  std::vector<Eigen::Vector3d> plane;
  for (int i = 0; i < 200; ++i) {
    for (int j = 0; j < 200; ++j) plane.push_back({0.005 * i, 0.005 * j, 0.0});
  }
  double voxel = 0.005;
  const auto out = VoxelAverageAtMost(plane, 5000, &voxel);
  EXPECT_LE(out.size(), 5000u);
  EXPECT_GT(out.size(), 2500u);  // not much coarser than needed
  EXPECT_GT(voxel, 0.005);
}

}  // namespace
}  // namespace simtree::reconstruction
