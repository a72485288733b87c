#include "simtree/reconstruction/detail/skeleton_smoothing.h"

#include <cmath>

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

// A branch bending through a quarter circle of 1 m radius, a node every 4.5 degrees.
Skeleton Arc() {
  Skeleton arc;
  for (int i = 0; i <= 20; ++i) {
    const double a = i * M_PI / 40;
    SkeletonNode n;
    n.position = {1.0 - std::cos(a), 0.0, std::sin(a)};
    n.parent = i - 1;
    arc.nodes.push_back(n);
  }
  return arc;
}

// Largest distance of a node from the arc it was sampled on.
double OffTheArc(const Skeleton& s) {
  double worst = 0.0;
  for (const SkeletonNode& n : s.nodes) {
    worst = std::max(worst, std::abs((n.position - Eigen::Vector3d(1, 0, 0)).norm() - 1.0));
  }
  return worst;
}

TEST(SkeletonSmoothing, KeepsABendWherePlainLaplacianSmoothingPullsItToItsChord) {
  Skeleton taubin = Arc();
  SmoothSkeleton(taubin, {});
  Skeleton plain = Arc();
  SmoothSkeleton(plain, {.inflate = 0.0});
  EXPECT_LT(OffTheArc(taubin), 0.001);
  EXPECT_GT(OffTheArc(plain), 3.0 * OffTheArc(taubin)) << OffTheArc(plain);
  EXPECT_GT(taubin.TotalLength(), plain.TotalLength());
}

}  // namespace
}  // namespace simtree::reconstruction
