#include "simtree/reconstruction/detail/space_colonization.h"

#include <gtest/gtest.h>

#include "reconstruction/reconstruction_fixtures.h"

namespace simtree::reconstruction {
namespace {

// Attraction points every `step` along segments, with their geodesic distance from the first.
void AddLine(std::vector<AttractionPoint>& points, const Eigen::Vector3d& a,
             const Eigen::Vector3d& b, double from_geodesic, double step = 0.02) {
  const int count = static_cast<int>((b - a).norm() / step);
  for (int i = 1; i <= count; ++i) {
    const double t = static_cast<double>(i) / count;
    points.push_back({a + t * (b - a), 5.0, 0.0, from_geodesic + t * (b - a).norm()});
  }
}

const ColonizationLengths kLengths{.step_m = 0.02,
                                   .influence_radius_m = 0.08,
                                   .kill_radius_m = 0.03,
                                   .geodesic_slack_m = 0.05,
                                   .bridge_gap_m = 0.25};

// Distance from p to the nearest node.
double NearestNode(const Skeleton& s, const Eigen::Vector3d& p) {
  double best = 1e9;
  for (const SkeletonNode& n : s.nodes) best = std::min(best, (n.position - p).norm());
  return best;
}

TEST(SpaceColonization, GrowsThroughAYAndForksOnce) {
  std::vector<AttractionPoint> points;
  AddLine(points, {0, 0, 0}, {0, 0, 1}, 0.0);
  AddLine(points, {0, 0, 1}, {0.5, 0, 1.5}, 1.0);
  AddLine(points, {0, 0, 1}, {-0.4, 0, 1.6}, 1.0);
  ColonizationStats stats;
  const Skeleton s = GrowByColonization(points, {0, 0, 0}, {0, 0, 1}, kLengths, {}, &stats);
  EXPECT_EQ(stats.unreached_weight, 0.0);
  EXPECT_EQ(stats.stuck_weight, 0.0);
  EXPECT_NEAR(stats.reached_weight, 5.0 * points.size(), 1e-9);
  for (const AttractionPoint& p : points) EXPECT_LT(NearestNode(s, p.position), 0.03);
  // Two long tips (SC may leave a one-step spur at the fork; pruning removes those).
  const auto children = s.Children();
  int long_tips = 0;
  for (const SkeletonChain& chain : SkeletonChains(s)) {
    if (!children[chain.nodes.back()].empty()) continue;
    long_tips += chain.nodes.size() > 5;
  }
  EXPECT_EQ(long_tips, 2);
  // Parents first, every node explains some points or bridges to them.
  for (int i = 1; i < s.size(); ++i) EXPECT_LT(s.nodes[i].parent, i);
}

TEST(SpaceColonization, ThePerceptionConeKeepsGrowthFromTurningBack) {
  // Points only below a root that faces up.
  std::vector<AttractionPoint> points;
  AddLine(points, {0, 0, -0.02}, {0, 0, -0.5}, 0.0);
  ColonizationOptions o;
  o.geodesic_consistency = false;  // test the cone alone
  o.bridge_gaps = false;
  const Skeleton coned = GrowByColonization(points, {0, 0, 0}, {0, 0, 1}, kLengths, o);
  EXPECT_EQ(coned.size(), 1);
  o.perception_half_angle_rad = 4.0;  // no cone: it grows down
  const Skeleton both = GrowByColonization(points, {0, 0, 0}, {0, 0, 1}, kLengths, o);
  double lowest = 0;
  for (const SkeletonNode& n : both.nodes) lowest = std::min(lowest, n.position.z());
  EXPECT_LT(lowest, -0.45);
}

TEST(SpaceColonization, GeodesicsKeepABranchFromJumpingToItsNeighbour) {
  // Two parallel stems 6 cm apart joined only at the base: the second is far along the scan.
  std::vector<AttractionPoint> points;
  AddLine(points, {0, 0, 0}, {0, 0, 1}, 0.0);
  AddLine(points, {0, 0, 0}, {0.3, 0, 0}, 0.0);
  AddLine(points, {0.3, 0, 0}, {0.3, 0, 0.3}, 0.3);
  AddLine(points, {0.3, 0, 0.3}, {0.06, 0, 0.6}, 0.6);  // comes back near the first stem
  const Skeleton s = GrowByColonization(points, {0, 0, 0}, {0, 0, 1}, kLengths);
  // No edge may join the stems across the 6 cm where they pass close.
  for (int i = 1; i < s.size(); ++i) {
    const Eigen::Vector3d& a = s.nodes[i].position;
    const Eigen::Vector3d& b = s.nodes[s.nodes[i].parent].position;
    const bool a_on_first = a.x() < 0.02 && a.z() > 0.5;
    const bool b_on_second = b.x() > 0.04 && b.z() > 0.5;
    EXPECT_FALSE(a_on_first && b_on_second) << i;
  }
}

TEST(SpaceColonization, BridgesAnOcclusionGapOnlyWhenAllowed) {
  std::vector<AttractionPoint> points;
  AddLine(points, {0, 0, 0}, {0, 0, 0.5}, 0.0);
  AddLine(points, {0, 0, 0.7}, {0, 0, 1.2}, 0.7);  // 20 cm hidden
  ColonizationStats bridged;
  const Skeleton with = GrowByColonization(points, {0, 0, 0}, {0, 0, 1}, kLengths, {}, &bridged);
  EXPECT_GE(bridged.bridges, 1);
  EXPECT_EQ(bridged.unreached_weight, 0.0);
  EXPECT_LT(NearestNode(with, {0, 0, 1.2}), 0.03);
  ColonizationStats cut;
  const Skeleton without =
      GrowByColonization(points, {0, 0, 0}, {0, 0, 1}, kLengths, {.bridge_gaps = false}, &cut);
  EXPECT_EQ(cut.bridges, 0);
  EXPECT_GT(cut.unreached_weight, 0.0);
  EXPECT_GT(NearestNode(without, {0, 0, 1.2}), 0.4);
}

TEST(SpaceColonization, NoPointsGiveJustTheRoot) {
  const Skeleton s = GrowByColonization({}, {1, 2, 3}, {0, 0, 1}, kLengths);
  ASSERT_EQ(s.size(), 1);
  EXPECT_TRUE(s.nodes[0].position.isApprox(Eigen::Vector3d(1, 2, 3)));
}

}  // namespace
}  // namespace simtree::reconstruction
