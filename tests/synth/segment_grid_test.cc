#include "simtree/synth/detail/segment_grid.h"

#include <random>

#include <gtest/gtest.h>

namespace simtree::synth {
namespace {

using Vec3 = Eigen::Vector3d;

TEST(SegmentDistance, ClosedForms) {
  // Crossing at right angles, 1 apart along z.
  EXPECT_NEAR(SegmentDistance({-1, 0, 0}, {1, 0, 0}, {0, -1, 1}, {0, 1, 1}), 1.0, 1e-12);
  // Parallel, overlapping, 0.5 apart.
  EXPECT_NEAR(SegmentDistance({0, 0, 0}, {2, 0, 0}, {1, 0.5, 0}, {3, 0.5, 0}), 0.5, 1e-12);
  // Parallel, end to end along one line with a gap of 1.
  EXPECT_NEAR(SegmentDistance({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}), 1.0, 1e-12);
  // Skew, closest points at the ends: (1,0,0) to (2,1,0)..(2,2,0) -> sqrt(2).
  EXPECT_NEAR(SegmentDistance({0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {2, 2, 0}), std::sqrt(2.0), 1e-12);
  // Point to segment and point to point.
  EXPECT_NEAR(SegmentDistance({0, 3, 0}, {0, 3, 0}, {-1, 0, 0}, {1, 0, 0}), 3.0, 1e-12);
  EXPECT_NEAR(SegmentDistance({0, 0, 0}, {0, 0, 0}, {3, 4, 0}, {3, 4, 0}), 5.0, 1e-12);
  // Touching at a shared end.
  EXPECT_NEAR(SegmentDistance({0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 1, 1}), 0.0, 1e-12);
}

TEST(SegmentDistance, MatchesDenseSampling) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  auto random = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 p0 = random(), p1 = random(), q0 = random(), q1 = random();
    double best = 1e9;
    constexpr int kSteps = 200;
    for (int i = 0; i <= kSteps; ++i) {
      for (int j = 0; j <= kSteps; ++j) {
        const Vec3 a = p0 + (p1 - p0) * i / kSteps, b = q0 + (q1 - q0) * j / kSteps;
        best = std::min(best, (a - b).norm());
      }
    }
    const double d = SegmentDistance(p0, p1, q0, q1);
    EXPECT_LE(d, best + 1e-12);
    EXPECT_GT(d, best - 0.02);  // the sampling is coarse
  }
}

TEST(SegmentGrid, FindsEverySegmentNearAQuery) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  SegmentGrid grid(0.1);
  std::vector<GridSegment> all;
  for (int i = 0; i < 500; ++i) {
    const Vec3 a(u(rng), u(rng), u(rng));
    const Vec3 b = a + 0.08 * Vec3(u(rng), u(rng), u(rng));
    all.push_back({a, b, 0.01, i, 0});
    grid.Add(all.back());
  }
  EXPECT_EQ(grid.size(), 500);
  EXPECT_DOUBLE_EQ(grid.max_radius(), 0.01);
  for (int q = 0; q < 50; ++q) {
    const Vec3 a(u(rng), u(rng), u(rng));
    const Vec3 b = a + 0.3 * Vec3(u(rng), u(rng), u(rng));
    const double reach = 0.05;
    std::set<int> found;
    grid.AnyNear(a, b, reach, [&](const GridSegment& s) {
      EXPECT_FALSE(found.contains(s.branch)) << "visited twice";
      if (SegmentDistance(a, b, s.a, s.b) < reach) found.insert(s.branch);
      return false;
    });
    std::set<int> expected;
    for (const GridSegment& s : all) {
      if (SegmentDistance(a, b, s.a, s.b) < reach) expected.insert(s.branch);
    }
    EXPECT_EQ(found, expected);
  }
  // Stops at the first hit.
  int visits = 0;
  EXPECT_TRUE(grid.AnyNear({-2, -2, -2}, {2, 2, 2}, 0.5, [&](const GridSegment&) {
    ++visits;
    return true;
  }));
  EXPECT_EQ(visits, 1);
  EXPECT_FALSE(grid.AnyNear({5, 5, 5}, {6, 6, 6}, 0.1, [](const GridSegment&) { return true; }));
}

}  // namespace
}  // namespace simtree::synth
