#include "simtree/synth/detail/camera_rig.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/tree_fixtures.h"
#include "simtree/core/error.h"

namespace simtree::synth {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

TEST(LookAt, OpenCvAxesLookAtTheTarget) {
  const Eigen::Isometry3d pose = LookAt({0, -2, 1}, {0, 0, 1});
  const Eigen::Matrix3d r = pose.linear();
  EXPECT_TRUE(r.isUnitary(1e-12));
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
  EXPECT_TRUE(r.col(2).isApprox(Eigen::Vector3d(0, 1, 0)));   // z forward
  EXPECT_TRUE(r.col(0).isApprox(Eigen::Vector3d(1, 0, 0)));   // x right
  EXPECT_TRUE(r.col(1).isApprox(Eigen::Vector3d(0, 0, -1)));  // y down
  // The target is straight ahead in the camera frame.
  const Eigen::Vector3d target_camera = pose.inverse() * Eigen::Vector3d(0, 0, 1);
  EXPECT_NEAR(target_camera.x(), 0, 1e-12);
  EXPECT_NEAR(target_camera.y(), 0, 1e-12);
  EXPECT_NEAR(target_camera.z(), 2, 1e-12);
  // Roll turns the image about the viewing axis and keeps it.
  const Eigen::Isometry3d rolled = LookAt({0, -2, 1}, {0, 0, 1}, Eigen::Vector3d::UnitZ(), 0.3);
  EXPECT_TRUE(rolled.linear().col(2).isApprox(r.col(2)));
  EXPECT_NEAR(std::acos(rolled.linear().col(0).dot(r.col(0))), 0.3, 1e-9);
}

TEST(LookAt, DegenerateViewsAreRefused) {
  EXPECT_THROW(LookAt({1, 1, 1}, {1, 1, 1}), InputError);
  EXPECT_THROW(LookAt({0, 0, 0}, {0, 0, 3}), InputError);
}

TEST(ScanViewPoses, RingOfViewsAimedAtTheTreeWithinTheRange) {
  const Tree tree = test::SmallTree();
  ScanRigOptions options;
  const auto poses = ScanViewPoses(tree, options, 7);
  ASSERT_EQ(poses.size(), 10u);
  std::vector<double> azimuths;
  for (const Eigen::Isometry3d& pose : poses) {
    const Eigen::Vector3d eye = pose.translation();
    const double distance = std::hypot(eye.x(), eye.y());
    EXPECT_GE(distance, options.min_distance_m - 1e-9);
    EXPECT_LE(distance, options.max_distance_m + 1e-9);
    EXPECT_GE(eye.z(), options.min_height_m);
    EXPECT_LE(eye.z(), options.max_height_m);
    // The trunk's middle is near the image centre (within the aim jitter and a margin).
    const Eigen::Vector3d trunk_middle_camera = pose.inverse() * Eigen::Vector3d(0, 0, 0.5);
    EXPECT_GT(trunk_middle_camera.z(), 0.0);
    const double off_axis =
        std::atan2(trunk_middle_camera.head<2>().norm(), trunk_middle_camera.z());
    EXPECT_LT(off_axis, 25 * kDegree);
    azimuths.push_back(std::atan2(eye.y(), eye.x()));
  }
  // Consecutive views are about 36 degrees apart.
  for (size_t i = 1; i < azimuths.size(); ++i) {
    double step = std::remainder(azimuths[i] - azimuths[i - 1], 2 * std::numbers::pi);
    EXPECT_NEAR(step, 36 * kDegree, 2 * options.azimuth_jitter_deg * kDegree + 1e-9);
  }
}

TEST(ScanViewPoses, SameSeedSamePosesOtherSeedOtherPoses) {
  const Tree tree = test::SmallTree();
  const auto a = ScanViewPoses(tree, {}, 3);
  const auto b = ScanViewPoses(tree, {}, 3);
  const auto c = ScanViewPoses(tree, {}, 4);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(a[i].matrix() == b[i].matrix());
  }
  EXPECT_FALSE(a[0].matrix().isApprox(c[0].matrix()));
}

TEST(ScanViewPoses, HardRigHasFewerViewsAndWiderGaps) {
  const Tree tree = test::SmallTree();
  const auto poses = ScanViewPoses(tree, ScanRigOptions::Hard(), 1);
  ASSERT_EQ(poses.size(), 7u);
  double widest = 0;
  for (size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Vector3d a = poses[i].translation(),
                          b = poses[(i + 1) % poses.size()].translation();
    widest = std::max(widest,
                      std::abs(std::remainder(std::atan2(b.y(), b.x()) - std::atan2(a.y(), a.x()),
                                              2 * std::numbers::pi)));
  }
  EXPECT_GT(widest, 52 * kDegree);
}

TEST(ScanViewPoses, BadOptionsAreRefused) {
  const Tree tree = test::SmallTree();
  ScanRigOptions options;
  options.views = 0;
  EXPECT_THROW(ScanViewPoses(tree, options, 1), InputError);
  options = {};
  options.min_distance_m = 3;
  options.max_distance_m = 2;
  EXPECT_THROW(ScanViewPoses(tree, options, 1), InputError);
}

TEST(PullCameraPose, StandsToTheSideOfThePullAndSeesTheTree) {
  const Tree tree = test::SmallTree();
  PullCameraOptions options;
  options.side_angle_deg = 90;
  const Eigen::Isometry3d pose = PullCameraPose(tree, {1, 0, 0}, options);
  const Eigen::Vector3d eye = pose.translation();
  // Turned 90 degrees from +X about Z: on the +Y side, so the pull is seen broadside.
  EXPECT_GT(eye.y(), 1.0);
  EXPECT_NEAR(eye.x(), 0.0, 1e-9);
  EXPECT_NEAR(std::abs(pose.linear().col(0).x()), 1.0, 0.05);  // the pull runs across the image
}

}  // namespace
}  // namespace simtree::synth
