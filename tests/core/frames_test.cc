#include "simtree/core/frames.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "core/tree_fixtures.h"

namespace simtree {
namespace {

void ExpectOrthonormalRightHanded(const Frame& f) {
  EXPECT_NEAR(f.u.norm(), 1, 1e-12);
  EXPECT_NEAR(f.v.norm(), 1, 1e-12);
  EXPECT_NEAR(f.u.dot(f.v), 0, 1e-12);
  EXPECT_TRUE(f.u.cross(f.v).isApprox(f.w, 1e-12));
}

TEST(Frames, VAlongTheBranchUNormalToTheParentPlane) {
  const Tree tree = test::SmallTree();
  for (const Branch& b : tree.branches) ExpectOrthonormalRightHanded(b.frame);
  EXPECT_TRUE(tree.trunk().frame.v.isApprox(Eigen::Vector3d::UnitZ()));
  // Trunk: parallel to its reference axis, so u falls back to world X.
  EXPECT_TRUE(tree.trunk().frame.u.isApprox(Eigen::Vector3d::UnitX()));
  // Branch 1 leans towards +X from a +Z trunk: its plane is XZ, so u is -Y (Z x X = Y... sign).
  const Frame& f1 = tree.branches[1].frame;
  EXPECT_TRUE(f1.v.isApprox(Eigen::Vector3d(1, 0, 1).normalized()));
  EXPECT_NEAR(std::abs(f1.u.y()), 1.0, 1e-12);
  EXPECT_TRUE(f1.u.isApprox(Eigen::Vector3d::UnitZ().cross(f1.v).normalized()));
  // w lies in the plane of the branch and its parent.
  EXPECT_NEAR(f1.w.y(), 0.0, 1e-12);
}

TEST(Frames, ParallelToParentUsesParentU) {
  const Frame f = FrameFromAxes({0, 0, 1}, {0, 0, 1}, {0, 1, 0});
  EXPECT_TRUE(f.u.isApprox(Eigen::Vector3d::UnitY()));
  ExpectOrthonormalRightHanded(f);
  // Fallback parallel to the axis too: any perpendicular.
  ExpectOrthonormalRightHanded(FrameFromAxes({0, 0, 1}, {0, 0, 1}, {0, 0, 2}));
}

TEST(Frames, LevelsFollowParents) {
  Tree tree = test::SmallTree();
  for (Branch& b : tree.branches) b.level = 7;
  AssignLevels(tree);
  EXPECT_EQ(tree.branches[0].level, 0);
  EXPECT_EQ(tree.branches[2].level, 1);
  EXPECT_EQ(tree.branches[3].level, 2);
}

}  // namespace
}  // namespace simtree
