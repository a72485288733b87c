#include "simtree/reconstruction/detail/branch_decomposition.h"

#include <gtest/gtest.h>

#include "reconstruction/reconstruction_fixtures.h"
#include "simtree/core/validate.h"
#include "simtree/reconstruction/detail/allometric_radii.h"

namespace simtree::reconstruction {
namespace {

Skeleton WithRadii(Skeleton s) {
  AssignRadii(s, 0, 0.1, 0.0, {}, 0.0, {.local_fits = false});
  return s;
}

TEST(BranchDecomposition, TheHeavierChildContinuesAndTheOtherStartsALevelDeeper) {
  const Skeleton y = WithRadii(test::YSkeleton());
  const Tree tree = DecomposeIntoBranches(y, {}, "test");
  ASSERT_EQ(tree.size(), 2);
  EXPECT_TRUE(FindProblems(tree).empty());
  const Branch& trunk = tree.branches[0];
  EXPECT_EQ(trunk.nodes.size(), 19u);  // root, stem, long branch
  EXPECT_TRUE(trunk.tip().position.isApprox(Eigen::Vector3d(0.4, 0, 1.7)));
  const Branch& side = tree.branches[1];
  EXPECT_EQ(side.parent, 0);
  EXPECT_EQ(side.parent_node, 10);
  EXPECT_EQ(side.level, 1);
  EXPECT_TRUE(side.base().position.isApprox(trunk.nodes[10].position));
  EXPECT_EQ(side.nodes.size(), 4u);
  EXPECT_NEAR(side.base().radius, y.nodes[19].radius, 1e-12);  // its own radius at the fork
  EXPECT_EQ(tree.metadata.source, "test");
}

TEST(BranchDecomposition, AmongComparableChildrenTheStraightestContinues) {
  // A stem forking into two equal branches, one straight on, one bent 50 degrees.
  Skeleton s;
  s.nodes.push_back({Eigen::Vector3d::Zero(), -1, 0.0, 1.0, 0.0});
  const int top = test::AddSkeletonChain(s, 0, {0, 0, 1}, 10);
  test::AddSkeletonChain(s, top, {0.6, 0, 1.5}, 6);  // longer, bent
  test::AddSkeletonChain(s, top, {0, 0, 1.7}, 6);    // a little shorter, straight on
  const Tree tree = DecomposeIntoBranches(WithRadii(s));
  ASSERT_EQ(tree.size(), 2);
  EXPECT_TRUE(tree.branches[0].tip().position.isApprox(Eigen::Vector3d(0, 0, 1.7)));
  // With only the weight deciding, the longer bent branch would lead.
  const Tree heaviest = DecomposeIntoBranches(WithRadii(s), {.comparable_share = 1.01});
  EXPECT_TRUE(heaviest.branches[0].tip().position.isApprox(Eigen::Vector3d(0.6, 0, 1.5)));
}

TEST(BranchDecomposition, ARootAloneIsNoTree) {
  Skeleton root;
  root.nodes.push_back({Eigen::Vector3d::Zero(), -1, 0.05, 0.0, 0.0});
  EXPECT_TRUE(DecomposeIntoBranches(root).empty());
}

}  // namespace
}  // namespace simtree::reconstruction
