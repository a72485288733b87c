#include "simtree/reconstruction/detail/cloud_scale.h"

#include <random>

#include <gtest/gtest.h>

namespace simtree::reconstruction {
namespace {

std::vector<Eigen::Vector3d> Plane(double spacing, double noise, int side = 120) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> gauss(0.0, noise > 0 ? noise : 1.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      points.push_back({spacing * i, spacing * j, noise > 0 ? gauss(rng) : 0.0});
    }
  }
  return points;
}

TEST(CloudScale, MeasuresTheSpacingOfAGrid) {
  const CloudScale scale = MeasureCloudScale(Plane(0.01, 0.0));
  EXPECT_NEAR(scale.spacing_m, 0.01, 1e-9);
  // The 6th neighbour of a square grid is at sqrt(2) or 2 spacings.
  EXPECT_GE(scale.neighbourhood_m, 0.0141);
  EXPECT_LE(scale.neighbourhood_m, 0.0201);
  EXPECT_NEAR(scale.roughness_m, 0.0, 1e-9);
}

TEST(CloudScale, RoughnessGrowsWithNoise) {
  const CloudScale quiet = MeasureCloudScale(Plane(0.01, 0.001));
  const CloudScale noisy = MeasureCloudScale(Plane(0.01, 0.003));
  EXPECT_GT(quiet.roughness_m, 0.0005);
  EXPECT_LT(quiet.roughness_m, 0.0015);
  EXPECT_GT(noisy.roughness_m, 2.0 * quiet.roughness_m);
}

TEST(CloudScale, ALargeCloudIsMeasuredOnASubsetAndScaledBack) {
  // Points scattered at random on a 2 m x 2 m square (a surface, as scans are).
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.0, 2.0);
  std::vector<Eigen::Vector3d> points(160000);
  for (auto& p : points) p = {u(rng), u(rng), 0.0};
  const CloudScale full = MeasureCloudScale(points, {.max_indexed_points = 200000});
  const CloudScale thinned = MeasureCloudScale(points, {.max_indexed_points = 40000});
  EXPECT_NEAR(thinned.spacing_m / full.spacing_m, 1.0, 0.1);
  EXPECT_NEAR(thinned.neighbourhood_m / full.neighbourhood_m, 1.0, 0.1);
}

TEST(CloudScale, TooFewPointsGiveZeros) {
  const std::vector<Eigen::Vector3d> two = {{0, 0, 0}, {1, 0, 0}};
  const CloudScale scale = MeasureCloudScale(two);
  EXPECT_EQ(scale.spacing_m, 0.0);
  EXPECT_EQ(scale.roughness_m, 0.0);
}

}  // namespace
}  // namespace simtree::reconstruction
