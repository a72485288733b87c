#include "simtree/reconstruction/detail/ground_plane.h"

#include <gtest/gtest.h>

#include "reconstruction/reconstruction_fixtures.h"

namespace simtree::reconstruction {
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

// A box's five faces (no bottom), `spacing` apart, standing on z = 0.
void AddBox(std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& corner, double size,
            double spacing) {
  const int n = static_cast<int>(size / spacing);
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const double a = i * spacing, b = j * spacing;
      points.push_back(corner + Eigen::Vector3d(a, b, size));
      points.push_back(corner + Eigen::Vector3d(a, 0, b));
      points.push_back(corner + Eigen::Vector3d(a, size, b));
      points.push_back(corner + Eigen::Vector3d(0, a, b));
      points.push_back(corner + Eigen::Vector3d(size, a, b));
    }
  }
}

// What a capture aimed at a crown sees low down: ground on one side only, two boxes by the trunk
// with more points than that ground, and stray returns far below it.
std::vector<Eigen::Vector3d> SceneWithBoxes() {
  auto points = test::CylinderPoints({0, 0, 0}, {0, 0, 1}, 2.0, 0.1, 0.02);
  for (double x = 0.3; x <= 2.0; x += 0.02) {
    for (double y = -1.0; y <= 1.0; y += 0.02) points.push_back({x, y, 0.0});
  }
  AddBox(points, {0.4, 0.3, 0.0}, 0.4, 0.01);
  AddBox(points, {-0.9, -0.5, 0.0}, 0.4, 0.01);
  for (int i = 0; i < 5; ++i) points.push_back({0.3 * i, -0.2 * i, -1.0 - 0.1 * i});
  return points;
}

TEST(GroundPlane, FindsGroundSeenOnOneSideBesideBoxesAndStrayReturns) {
  const auto points = SceneWithBoxes();
  const GroundPlane ground = FindGroundPlane(points);
  ASSERT_TRUE(ground.found) << ground.plane_width_m << " " << ground.standing_width_m << " "
                            << ground.covered_share;
  EXPECT_GT(ground.normal.z(), 0.99);
  EXPECT_NEAR(ground.HeightAt(1.0, 0.0), 0.0, 0.005);
  EXPECT_LT(ground.covered_share, 0.5);
  // Box tops and the trunk above the clearance stay.
  for (size_t i = 0; i < points.size(); ++i) {
    if (points[i].z() > 0.1) {
      EXPECT_FALSE(ground.is_ground[i]) << i;
    }
  }
}

TEST(GroundPlane, ASegmentedTreeHasNoGround) {
  EXPECT_FALSE(FindGroundPlane(TrunkOnGround(false)).found);
  EXPECT_FALSE(FindGroundPlane(std::vector<Eigen::Vector3d>{}).found);
}

}  // namespace
}  // namespace simtree::reconstruction
