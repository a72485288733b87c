#include "simtree/registration/detail/l1_medial_skeleton.h"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "preprocessing/option_fixtures.h"

namespace simtree::registration {
namespace {

// Points all around a cylinder of `radius` along z from 0 to `length`.
std::vector<Eigen::Vector3d> Tube(double radius, double length, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 4000; ++i) {
    const double a = 2 * std::numbers::pi * u(rng);
    points.emplace_back(radius * std::cos(a), radius * std::sin(a), length * u(rng));
  }
  return points;
}

TEST(L1MedialSkeleton, ContractsATubeToItsAxis) {
  const auto input = Tube(0.04, 1.0, 1);
  SkeletonOptions options;
  // h above the tube's radius: the kernel (h/2) spans the cross-section, as Huang et al. need.
  options.initial_radius_m = 0.1;
  const Skeleton skeleton = L1MedialSkeleton(input, options);
  ASSERT_GT(skeleton.points.size(), 10u);
  int near_axis = 0;
  for (const auto& p : skeleton.points) {
    if (std::hypot(p.x(), p.y()) < 0.01) ++near_axis;
  }
  // The ends contract less (the neighbourhood is one-sided there).
  EXPECT_GT(near_axis, 0.8 * skeleton.points.size());
  // Spread along the axis, not clumped: the repulsion term at work.
  double lo = 1, hi = 0;
  for (const auto& p : skeleton.points) {
    lo = std::min(lo, p.z());
    hi = std::max(hi, p.z());
  }
  EXPECT_LT(lo, 0.15);
  EXPECT_GT(hi, 0.85);
  for (double s : skeleton.directionality) {
    EXPECT_GE(s, 1.0 / 3.0 - 1e-9);
    EXPECT_LE(s, 1.0 + 1e-9);
  }
}

TEST(L1MedialSkeleton, RepulsionSpreadsThePoints) {
  const auto input = Tube(0.04, 1.0, 2);
  SkeletonOptions with;
  with.initial_radius_m = 0.06;
  SkeletonOptions without = with;
  without.repulsion_mu = 0.0;
  // Without repulsion the points collapse onto fewer places, and more of them merge.
  EXPECT_GT(L1MedialSkeleton(input, with).points.size(),
            L1MedialSkeleton(input, without).points.size());
}

TEST(L1MedialSkeleton, IsDeterministicAndHandlesEmptyInput) {
  const auto input = Tube(0.04, 0.5, 3);
  const Skeleton a = L1MedialSkeleton(input);
  const Skeleton b = L1MedialSkeleton(input);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i) EXPECT_EQ(a.points[i], b.points[i]);
  EXPECT_TRUE(L1MedialSkeleton({}).points.empty());
  EXPECT_EQ(L1MedialSkeleton({Eigen::Vector3d(1, 2, 3)}).points.size(), 1u);
}

TEST(L1MedialSkeleton, NonsenseOptionsAreRefused) {
  using test::RefusedField;
  EXPECT_EQ(RefusedField(SkeletonOptions{}), "");
  EXPECT_EQ(RefusedField(SkeletonOptions{.repulsion_mu = 0.6}), "repulsion_mu");
  EXPECT_EQ(RefusedField(SkeletonOptions{.max_points = 10, .min_points = 20}), "max_points");
  EXPECT_EQ(RefusedField(SkeletonOptions{.initial_radius_m = 0}), "initial_radius_m");
  EXPECT_THROW(L1MedialSkeleton({Eigen::Vector3d::Zero()}, SkeletonOptions{.rounds = 0}),
               InputError);
}

}  // namespace
}  // namespace simtree::registration
