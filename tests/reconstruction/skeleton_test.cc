#include "simtree/reconstruction/detail/skeleton.h"

#include <gtest/gtest.h>

#include "reconstruction/reconstruction_fixtures.h"

namespace simtree::reconstruction {
namespace {

TEST(Skeleton, ChildrenLengthsChainsAndTheHeaviestPath) {
  const Skeleton y = test::YSkeleton();
  ASSERT_EQ(y.size(), 1 + 10 + 8 + 3);
  const auto children = y.Children();
  EXPECT_EQ(children[10].size(), 2u);  // the fork
  const auto below = y.SubtreeLengths();
  const double long_branch = (Eigen::Vector3d(0.4, 0, 1.7) - Eigen::Vector3d(0, 0, 1)).norm();
  const double short_branch = (Eigen::Vector3d(-0.2, 0.1, 1.25) - Eigen::Vector3d(0, 0, 1)).norm();
  EXPECT_NEAR(below[0], 1.0 + long_branch + short_branch, 1e-9);
  EXPECT_NEAR(y.TotalLength(), below[0], 1e-9);
  const auto chains = SkeletonChains(y);
  ASSERT_EQ(chains.size(), 3u);
  EXPECT_EQ(chains[0].nodes.front(), 0);
  EXPECT_EQ(chains[0].nodes.back(), 10);
  for (size_t c = 1; c < chains.size(); ++c) EXPECT_EQ(chains[c].nodes.front(), 10);
  const auto path = HeaviestPath(y);
  EXPECT_EQ(path.size(), 1u + 10 + 8);  // through the long branch
  EXPECT_EQ(path.back(), 18);
}

TEST(Skeleton, WithoutKeepsOrderAndLinks) {
  const Skeleton y = test::YSkeleton();
  std::vector<char> remove(y.nodes.size(), 0);
  for (int i = 19; i < y.size(); ++i) remove[i] = 1;  // the short branch
  const Skeleton kept = y.Without(remove);
  ASSERT_EQ(kept.size(), 19);
  for (int i = 1; i < kept.size(); ++i) {
    EXPECT_EQ(kept.nodes[i].parent, i - 1);  // one chain now
  }
  EXPECT_EQ(SkeletonChains(kept).size(), 1u);
}

}  // namespace
}  // namespace simtree::reconstruction
