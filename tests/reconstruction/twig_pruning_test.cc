#include "simtree/reconstruction/detail/twig_pruning.h"

#include <gtest/gtest.h>

#include "reconstruction/reconstruction_fixtures.h"

namespace simtree::reconstruction {
namespace {

TEST(TwigPruning, RemovesAnUnsupportedTwigAndKeepsBranches) {
  Skeleton y = test::YSkeleton();
  for (int i = 19; i < y.size(); ++i) y.nodes[i].support = 0.5;  // the short branch: 1.5 points
  TwigPruningStats stats;
  const Skeleton pruned = PruneTwigs(y, {}, &stats);
  EXPECT_EQ(stats.twigs_removed, 1);
  EXPECT_EQ(stats.nodes_removed, 3);
  EXPECT_EQ(pruned.size(), y.size() - 3);
  // Well supported: nothing goes.
  const Skeleton kept = PruneTwigs(test::YSkeleton(), {});
  EXPECT_EQ(kept.size(), test::YSkeleton().size());
}

TEST(TwigPruning, RemovesABumpOnThickWoodAndSparseTwigs) {
  Skeleton y = test::YSkeleton();
  for (SkeletonNode& n : y.nodes) n.thickness = 0.25;  // a 25 cm trunk: the 30 cm twig is a bump
  EXPECT_EQ(PruneTwigs(y, {}).size(), y.size() - 3);
  // Per metre: 10 points a node every ~10 cm is 100 per metre; ask for more.
  const Skeleton sparse = PruneTwigs(test::YSkeleton(), {.min_support_per_m = 150.0});
  EXPECT_LT(sparse.size(), test::YSkeleton().size());
}

TEST(TwigPruning, NeverRemovesTheTrunkOfAnUnbranchedSkeleton) {
  Skeleton line;
  line.nodes.push_back({Eigen::Vector3d::Zero(), -1, 0.0, 0.0, 0.0});
  test::AddSkeletonChain(line, 0, {0, 0, 1}, 5, 0.0);  // no support at all
  EXPECT_EQ(PruneTwigs(line, {}).size(), line.size());
}

}  // namespace
}  // namespace simtree::reconstruction
