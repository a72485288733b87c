#include "simtree/reconstruction/detail/skeleton_smoothing.h"

#include <gtest/gtest.h>

#include "reconstruction/reconstruction_fixtures.h"

namespace simtree::reconstruction {
namespace {

TEST(SkeletonSmoothing, StraightensAZigzagAndKeepsEndsAndForks) {
  Skeleton y = test::YSkeleton();
  for (int i = 1; i < 10; ++i) y.nodes[i].position.x() += (i % 2 ? 0.01 : -0.01);
  const Skeleton before = y;
  SmoothSkeleton(y, {.iterations = 10, .weight = 0.5});
  double zigzag = 0.0;
  for (int i = 1; i < 10; ++i) zigzag = std::max(zigzag, std::abs(y.nodes[i].position.x()));
  EXPECT_LT(zigzag, 0.004);
  EXPECT_TRUE(y.nodes[0].position.isApprox(before.nodes[0].position));
  EXPECT_TRUE(y.nodes[10].position.isApprox(before.nodes[10].position));  // the fork
  EXPECT_TRUE(y.nodes[18].position.isApprox(before.nodes[18].position));  // a tip
  // Straight chains stay where they are.
  for (int i = 11; i < 18; ++i) EXPECT_TRUE(y.nodes[i].position.isApprox(before.nodes[i].position));
  Skeleton off = before;
  SmoothSkeleton(off, {.iterations = 0});
  EXPECT_TRUE(off.nodes[3].position.isApprox(before.nodes[3].position));
}

}  // namespace
}  // namespace simtree::reconstruction
