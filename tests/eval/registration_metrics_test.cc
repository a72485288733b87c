#include "simtree/eval/registration_metrics.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "simtree/core/error.h"

namespace simtree::eval {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Tree TwoBranchTree() {
  Tree tree;
  Branch trunk;
  trunk.nodes = {{Eigen::Vector3d(0, 0, 0), 0.05}, {Eigen::Vector3d(0, 0, 2), 0.03}};
  Branch side;
  side.id = 1;
  side.parent = 0;
  side.parent_node = 1;
  side.level = 1;
  side.nodes = {{Eigen::Vector3d(0, 0, 2), 0.02}, {Eigen::Vector3d(1, 0, 2), 0.01}};
  tree.branches = {trunk, side};
  return tree;
}

TEST(RegistrationMetrics, SamplesEveryBranchAtTheSpacing) {
  const auto points = TreeSamplePoints(TwoBranchTree(), 0.1);
  // 2 m trunk and 1 m branch at 10 cm: 20 + 10 segments, plus both tips.
  EXPECT_EQ(points.size(), 32u);
  for (const auto& p : points) {
    EXPECT_TRUE((p.x() == 0 && p.y() == 0) || std::abs(p.z() - 2) < 1e-12) << p.transpose();
  }
  EXPECT_THROW(TreeSamplePoints(TwoBranchTree(), 0.0), InputError);
}

TEST(RegistrationMetrics, IdentityHasNoError) {
  const auto points = TreeSamplePoints(TwoBranchTree(), 0.05);
  const PoseError e = ErrorAtTree(Eigen::Isometry3d::Identity(), points);
  EXPECT_EQ(e.rotation_deg, 0.0);
  EXPECT_EQ(e.tree_rms_m, 0.0);
  EXPECT_EQ(e.tree_max_m, 0.0);
  EXPECT_TRUE(e.Within());
}

TEST(RegistrationMetrics, RotationAboutTheTrunkMatchesTheClosedForm) {
  // Points on a circle of radius r about the z axis, turned by theta about it: each moves by the
  // chord 2 r sin(theta / 2).
  std::vector<Eigen::Vector3d> circle;
  const double r = 0.7;
  for (int k = 0; k < 36; ++k) {
    circle.emplace_back(r * std::cos(k * 10 * kDeg), r * std::sin(k * 10 * kDeg), 1.0);
  }
  Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
  turn.linear() = Eigen::AngleAxisd(3 * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const PoseError e = ErrorAtTree(turn, circle);
  EXPECT_NEAR(e.rotation_deg, 3.0, 1e-9);
  EXPECT_NEAR(e.tree_rms_m, 2 * r * std::sin(1.5 * kDeg), 1e-12);
  EXPECT_NEAR(e.tree_max_m, e.tree_rms_m, 1e-12);
  EXPECT_NEAR(e.centroid_m, 0.0, 1e-12);  // the centroid is on the axis
  EXPECT_FALSE(e.Within(2.0, 0.05));      // 3 degrees is over the bar
}

TEST(RegistrationMetrics, PairErrorIsZeroForTheTruePose) {
  const auto points = TreeSamplePoints(TwoBranchTree(), 0.05);
  Eigen::Isometry3d world_from_a = Eigen::Isometry3d::Identity();
  world_from_a.linear() =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  world_from_a.translation() = Eigen::Vector3d(2, -1, 1.3);
  Eigen::Isometry3d world_from_b = Eigen::Isometry3d::Identity();
  world_from_b.linear() = Eigen::AngleAxisd(2.9, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  world_from_b.translation() = Eigen::Vector3d(-2.5, 0.3, 1.1);
  const Eigen::Isometry3d b_from_a = world_from_b.inverse() * world_from_a;
  const PoseError right = PairPoseError(b_from_a, world_from_a, world_from_b, points);
  EXPECT_NEAR(right.rotation_deg, 0.0, 1e-6);
  EXPECT_NEAR(right.tree_rms_m, 0.0, 1e-9);

  // A 1 cm shift along the target camera's x moves every tree point by 1 cm.
  Eigen::Isometry3d shifted = b_from_a;
  shifted.pretranslate(Eigen::Vector3d(0.01, 0, 0));
  const PoseError wrong = PairPoseError(shifted, world_from_a, world_from_b, points);
  EXPECT_NEAR(wrong.rotation_deg, 0.0, 1e-6);
  EXPECT_NEAR(wrong.tree_rms_m, 0.01, 1e-9);
  EXPECT_NEAR(wrong.centroid_m, 0.01, 1e-9);
}

TEST(RegistrationMetrics, ViewErrorIsRelativeToTheAnchor) {
  const auto points = TreeSamplePoints(TwoBranchTree(), 0.05);
  Eigen::Isometry3d world_from_anchor = Eigen::Isometry3d::Identity();
  world_from_anchor.translation() = Eigen::Vector3d(0, -2.5, 1.2);
  Eigen::Isometry3d world_from_view = Eigen::Isometry3d::Identity();
  world_from_view.linear() = Eigen::AngleAxisd(1.2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  world_from_view.translation() = Eigen::Vector3d(2.1, 1.0, 1.4);
  // Any registration frame: the truth moved by an arbitrary rigid transform.
  Eigen::Isometry3d frame_from_world = Eigen::Isometry3d::Identity();
  frame_from_world.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()).toRotationMatrix();
  frame_from_world.translation() = Eigen::Vector3d(5, 6, 7);
  const PoseError e =
      ViewPoseError(frame_from_world * world_from_view, frame_from_world * world_from_anchor,
                    world_from_view, world_from_anchor, points);
  EXPECT_NEAR(e.rotation_deg, 0.0, 1e-6);
  EXPECT_NEAR(e.tree_rms_m, 0.0, 1e-9);
}

TEST(RegistrationMetrics, AngleGapIsTheTurnAroundTheTree) {
  auto looking = [](double yaw, double pitch) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    // OpenCV camera looking along the horizontal direction `yaw`, pitched up by `pitch`.
    const Eigen::Vector3d forward(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw),
                                  std::sin(pitch));
    const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
    pose.linear().col(0) = right;
    pose.linear().col(1) = forward.cross(right);
    pose.linear().col(2) = forward;
    return pose;
  };
  EXPECT_NEAR(ViewAngleDeg(looking(0, 0), looking(144 * kDeg, 0.2)), 144.0, 1e-9);
  EXPECT_NEAR(ViewAngleDeg(looking(0.3, 0.1), looking(0.3 + kDeg * 180, -0.1)), 180.0, 1e-6);
}

TEST(RegistrationMetrics, EmptyTreePointsAreAnError) {
  EXPECT_THROW(ErrorAtTree(Eigen::Isometry3d::Identity(), {}), InputError);
}

}  // namespace
}  // namespace simtree::eval
