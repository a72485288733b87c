#include "simtree/reconstruction/ground_plane.h"

#include <gtest/gtest.h>

#include "reconstruction/reconstruction_fixtures.h"

namespace simtree {
namespace {

std::vector<Eigen::Vector3d> TrunkOnGround(bool ground) {
  auto points = test::CylinderPoints({0, 0, 0}, {0, 0, 1}, 2.0, 0.1, 0.02);
  if (ground) {
    for (int i = -30; i <= 30; ++i) {
      for (int j = -30; j <= 30; ++j) {
        if (i * i + j * j > 25) points.push_back({0.05 * i, 0.05 * j, 0.01 * ((i + j) % 2)});
      }
    }
  }
  return points;
}

TEST(GroundPlane, FindsTheGroundAroundATrunk) {
  const auto points = TrunkOnGround(true);
  const GroundPlane ground = FindGroundPlane(points);
  ASSERT_TRUE(ground.found);
  EXPECT_GT(ground.normal.z(), 0.99);
  EXPECT_NEAR(ground.HeightAt(0.5, 0.5), 0.005, 0.01);
  EXPECT_GT(ground.ground_points, 3000u);
  // The trunk stays (its lowest ring is on the ground, nothing above it is).
  for (size_t i = 0; i < points.size(); ++i) {
    if (points[i].z() > 0.05) {
      EXPECT_FALSE(ground.is_ground[i]) << i;
    }
  }
}

TEST(GroundPlane, ASegmentedTreeHasNoGround) {
  EXPECT_FALSE(FindGroundPlane(TrunkOnGround(false)).found);
  EXPECT_FALSE(FindGroundPlane(std::vector<Eigen::Vector3d>{}).found);
}

}  // namespace
}  // namespace simtree
