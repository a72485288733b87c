#include "simtree/reconstruction/detail/allometric_radii.h"

#include <cmath>

#include <gtest/gtest.h>

#include "reconstruction/reconstruction_fixtures.h"

namespace simtree::reconstruction {
namespace {

TEST(AllometricRadii, PipeModelHoldsAtForksAndAnchorIsKept) {
  Skeleton y = test::YSkeleton();
  RadiusOptions options;
  options.local_fits = false;
  options.pipe_exponent = 2.5;
  RadiusStats stats;
  AssignRadii(y, 5, 0.1, 0.0, {}, 0.0, options, &stats);
  EXPECT_NEAR(y.nodes[5].radius, 0.1, 1e-12);
  EXPECT_EQ(stats.anchor_node, 5);
  // The pipe model: r^n is proportional to the weight a node carries, which adds up at forks.
  const double n = options.pipe_exponent;
  const auto w = AllometricWeights(y, options.tip_length_m);
  for (int i = 0; i < y.size(); ++i) {
    EXPECT_NEAR(std::pow(y.nodes[i].radius / 0.1, n), w[i] / w[5], 1e-9) << i;
  }
  const double edges = (y.nodes[11].position - y.nodes[10].position).norm() +
                       (y.nodes[19].position - y.nodes[10].position).norm();
  EXPECT_NEAR(w[10], w[11] + w[19] + edges, 1e-12);
  // Taper: radii never grow towards the tips; the long branch is thicker than the short one.
  for (int i = 1; i < y.size(); ++i)
    EXPECT_LE(y.nodes[i].radius, y.nodes[y.nodes[i].parent].radius);
  EXPECT_GT(y.nodes[11].radius, y.nodes[19].radius);
  EXPECT_GE(y.nodes.back().radius, options.min_radius_m);
}

TEST(AllometricRadii, WithoutAnAnchorTheRootTakesTheFallback) {
  Skeleton y = test::YSkeleton();
  AssignRadii(y, -1, 0.0, 0.07, {}, 0.0, {.local_fits = false});
  EXPECT_NEAR(y.nodes[0].radius, 0.07, 1e-12);
}

TEST(AllometricRadii, LocalFitsCorrectABranchTheModelGetsWrongAndRecentreIt) {
  // The long branch of the Y is scanned as a 4 cm cylinder whose axis is 1 cm beside the skeleton.
  Skeleton y = test::YSkeleton();
  const Eigen::Vector3d fork(0, 0, 1), tip(0.4, 0, 1.7);
  const Eigen::Vector3d shift(0, 0.01, 0);
  const auto points =
      test::CylinderPoints(fork + shift, tip - fork, (tip - fork).norm(), 0.04, 0.005, 0.001);
  Skeleton model_only = y;
  AssignRadii(model_only, 5, 0.1, 0.0, {}, 0.0, {.local_fits = false});
  RadiusStats stats;
  AssignRadii(y, 5, 0.1, 0.0, points, 0.001, {}, &stats);
  EXPECT_GE(stats.chains_fitted, 1);
  EXPECT_GE(stats.nodes_fitted, 3);
  // Inner nodes of the long branch get ~4 cm (the model alone says something else).
  EXPECT_NEAR(y.nodes[14].radius, 0.04, 0.006);
  EXPECT_GT(std::abs(model_only.nodes[14].radius - 0.04), 0.01);
  // ... and move onto the scanned axis.
  EXPECT_NEAR(y.nodes[14].position.y(), 0.01, 0.003);
  // The trunk chain, which holds the anchor, keeps the model (the cylinder is the better
  // measurement there) and the stem is not moved (no points).
  EXPECT_NEAR(y.nodes[5].radius, 0.1, 1e-12);
  EXPECT_TRUE(y.nodes[5].position.isApprox(test::YSkeleton().nodes[5].position));
}

TEST(AllometricRadii, WeightsAddUpAtForks) {
  const Skeleton y = test::YSkeleton();
  const auto w = AllometricWeights(y, 0.05);
  EXPECT_NEAR(w.back(), 0.05, 1e-12);  // a tip
  EXPECT_NEAR(w[0], y.TotalLength() + 2 * 0.05, 1e-9);
}

}  // namespace
}  // namespace simtree::reconstruction
