#include "simtree/registration/detail/trunk.h"

#include <cmath>

#include <gtest/gtest.h>

#include "preprocessing/option_fixtures.h"
#include "preprocessing/preprocessing_fixtures.h"

namespace simtree::registration {
namespace {

const Eigen::Vector3d kUp = -Eigen::Vector3d::UnitY();

// The camera's half of a tilted cylinder from `a` to `b` (camera frame), as AddTrunk but along
// any axis.
void AddLimb(open3d::geometry::PointCloud& cloud, const Eigen::Vector3d& a,
             const Eigen::Vector3d& b, double radius, double spacing) {
  const Eigen::Vector3d d = (b - a).normalized();
  const Eigen::Vector3d toward = (-(a + b) / 2).normalized();  // towards the camera
  Eigen::Vector3d e1 = (toward - toward.dot(d) * d).normalized();
  const Eigen::Vector3d e2 = d.cross(e1);
  for (double s = 0; s <= (b - a).norm(); s += spacing) {
    for (double t = -1.4; t <= 1.4; t += spacing / radius) {
      cloud.points_.push_back(a + s * d + radius * (std::cos(t) * e1 + std::sin(t) * e2));
    }
  }
}

// A trunk from the ground (y = 1.2) up 1 m, forking into two limbs; camera frame.
open3d::geometry::PointCloud ForkedTree(double spacing) {
  open3d::geometry::PointCloud cloud;
  test::AddTrunk(cloud, 0.0, 2.5, 0.07, 1.0, spacing, 0.0, 1);
  const Eigen::Vector3d fork(0.0, 0.2, 2.5);
  AddLimb(cloud, fork, fork + Eigen::Vector3d(0.5, -0.8, 0.0), 0.05, spacing);
  AddLimb(cloud, fork, fork + Eigen::Vector3d(-0.5, -0.8, 0.1), 0.05, spacing);
  return cloud;
}

TEST(Trunk, FindsTheTrunkAndItsFork) {
  const auto cloud = ForkedTree(0.01);
  std::string why;
  const auto trunk = FindTrunk(cloud, kUp, 0.01, {}, &why);
  ASSERT_TRUE(trunk) << why;
  EXPECT_TRUE(trunk->fork_found);
  EXPECT_GT(trunk->axis.dot(kUp), std::cos(3.0 * M_PI / 180));
  // The fork is 1 m above the ground (y = 0.2). The slices see it where the arms' outline has
  // grown wider than the trunk and stayed so for confirm_slices: 13 cm (3 slices) above it here.
  EXPECT_NEAR(trunk->branch_point.y(), 0.2, 0.15);
  EXPECT_LT(trunk->branch_point.y(), 0.2);  // never below the fork (y grows downwards)
  EXPECT_NEAR(trunk->visible_width_m, 0.14, 0.02);
}

TEST(Trunk, CylinderRecoversTheAxisFromOneSide) {
  const auto cloud = ForkedTree(0.008);
  const auto trunk = FindTrunk(cloud, kUp, 0.008);
  ASSERT_TRUE(trunk);
  const auto cylinder = FitTrunkCylinder(cloud, *trunk);
  ASSERT_TRUE(cylinder);
  EXPECT_NEAR(cylinder->radius_m, 0.07, 0.003);
  // The axis is x = 0, z = 2.5, not the visible surface's centroid 4.5 cm in front of it.
  const Eigen::Vector3d p = cylinder->point;
  EXPECT_NEAR(p.x(), 0.0, 0.003);
  EXPECT_NEAR(p.z(), 2.5, 0.003);
  EXPECT_GT(std::abs(cylinder->axis.dot(kUp)), std::cos(1.0 * M_PI / 180));
  EXPECT_LT(cylinder->rms_m, 0.002);
}

TEST(Trunk, KeyRegionIsASphereAroundTheFork) {
  const auto cloud = ForkedTree(0.01);
  const auto trunk = FindTrunk(cloud, kUp, 0.01);
  ASSERT_TRUE(trunk);
  const KeyRegion region = KeyRegionOf(*trunk, cloud, kUp, {.radius_m = 0.3});
  EXPECT_EQ(region.center, trunk->branch_point);
  const auto inside = PointsInside(cloud, region);
  EXPECT_GT(inside.size(), 100u);
  for (size_t i : inside) EXPECT_LE((cloud.points_[i] - region.center).norm(), 0.3);
  // Automatic radius: a quarter of the visible height (about 1.8 m), within its bounds.
  EXPECT_NEAR(KeyRegionOf(*trunk, cloud, kUp).radius_m, 0.45, 0.05);
}

TEST(Trunk, NoUprightStemMeansNoTrunk) {
  // A lying branch: no slice column stands on the bottom.
  open3d::geometry::PointCloud cloud;
  AddLimb(cloud, Eigen::Vector3d(-0.8, 0.0, 2.5), Eigen::Vector3d(0.8, 0.05, 2.5), 0.04, 0.01);
  std::string why;
  EXPECT_FALSE(FindTrunk(cloud, kUp, 0.01, {}, &why));
  EXPECT_NE(why.find("no trunk"), std::string::npos) << why;
  // Too few points.
  open3d::geometry::PointCloud few;
  few.points_.resize(5, Eigen::Vector3d(0, 0, 2));
  EXPECT_FALSE(FindTrunk(few, kUp, 0.01, {}, &why));
}

TEST(Trunk, NonsenseOptionsAreRefused) {
  using test::RefusedField;
  EXPECT_EQ(RefusedField(TrunkOptions{}), "");
  EXPECT_EQ(RefusedField(TrunkOptions{.slice_height_m = 0}), "slice_height_m");
  EXPECT_EQ(RefusedField(TrunkOptions{.min_arm_share = 1.5}), "min_arm_share");
  EXPECT_EQ(RefusedField(CylinderFitOptions{}), "");
  EXPECT_EQ(RefusedField(CylinderFitOptions{.min_points = 4}), "min_points");
  EXPECT_EQ(RefusedField(KeyRegionOptions{}), "");
  EXPECT_EQ(RefusedField(KeyRegionOptions{.min_radius_m = 2.0}), "max_radius_m");  // < min
  open3d::geometry::PointCloud cloud;
  EXPECT_THROW(FindTrunk(cloud, -Eigen::Vector3d::UnitY(), 0.01, {.max_gap_slices = -1}),
               InputError);
}

}  // namespace
}  // namespace simtree::registration
