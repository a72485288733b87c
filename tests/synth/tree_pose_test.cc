#include "simtree/synth/detail/tree_pose.h"

#include <gtest/gtest.h>

#include "core/tree_fixtures.h"

namespace simtree::synth {
namespace {

TEST(TreePose, RestPoseHoldsEveryNodeInFileOrder) {
  const Tree tree = test::SmallTree();
  const TreePose pose(tree);
  EXPECT_EQ(pose.branch_count(), tree.size());
  EXPECT_EQ(pose.node_count(), tree.NodeCount());
  for (const Branch& b : tree.branches) {
    ASSERT_EQ(pose.node_count(b.id), static_cast<int>(b.nodes.size()));
    for (size_t i = 0; i < b.nodes.size(); ++i) {
      EXPECT_EQ(pose.node(b.id, static_cast<int>(i)), b.nodes[i].position);
    }
  }
  EXPECT_EQ(pose.offset(1), static_cast<int>(tree.branches[0].nodes.size()));
}

TEST(TreePose, PointAtFollowsRestArcLengthOnTheDeformedNodes) {
  const Tree tree = test::SmallTree();
  TreePose pose(tree);
  // At rest, the same as the branch's own interpolation.
  for (double s : {0.0, 0.1, 0.37, 0.6, 5.0}) {
    EXPECT_LT((pose.PointAt(tree, 1, s) - tree.branches[1].PointAt(s)).norm(), 1e-12) << s;
  }
  // Shift the trunk's third node: a point halfway to it moves half as far.
  pose.node(0, 2) += Eigen::Vector3d(0.1, 0, 0);
  const Eigen::Vector3d p = pose.PointAt(tree, 0, 0.375);
  EXPECT_NEAR(p.x(), 0.05, 1e-12);
  EXPECT_NEAR(p.z(), 0.375, 1e-12);
  const Eigen::Vector3d t = pose.TangentAt(tree, 0, 0.375);
  EXPECT_NEAR(t.norm(), 1.0, 1e-12);
  EXPECT_GT(t.x(), 0.0);
}

}  // namespace
}  // namespace simtree::synth
