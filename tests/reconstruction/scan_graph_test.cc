#include "simtree/reconstruction/detail/scan_graph.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace simtree::reconstruction {
namespace {

// Points every 1 cm along x, with a gap of `gap` metres after x = 0.5.
std::vector<Eigen::Vector3d> LineWithGap(double gap) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= 50; ++i) points.push_back({0.01 * i, 0, 0});
  for (int i = 0; i <= 50; ++i) points.push_back({0.5 + gap + 0.01 * i, 0, 0});
  return points;
}

TEST(ScanGraph, LinksNeighboursAndMeasuresGeodesics) {
  const auto points = LineWithGap(0.01);
  const PointIndex index(points);
  const ScanGraph graph = BuildScanGraph(points, index, {.neighbour_radius_m = 0.015});
  EXPECT_EQ(graph.pieces, 1);
  EXPECT_EQ(graph.bridges, 0);
  const std::vector<int> roots = {0};
  const GeodesicField field = GeodesicDistances(graph, roots);
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR(field.distance[i], points[i].x(), 1e-6) << i;
  }
  EXPECT_EQ(field.predecessor[0], -1);
  EXPECT_EQ(field.predecessor[1], 0);
}

TEST(ScanGraph, BridgesGapsUpToTheLimitOnly) {
  const auto points = LineWithGap(0.1);
  const PointIndex index(points);
  ScanGraphOptions options{.neighbour_radius_m = 0.015, .max_gap_m = 0.2};
  const ScanGraph bridged = BuildScanGraph(points, index, options);
  EXPECT_EQ(bridged.pieces, 2);
  EXPECT_EQ(bridged.bridges, 1);
  EXPECT_NEAR(bridged.longest_bridge_m, 0.1, 1e-6);
  const std::vector<int> roots = {0};
  const GeodesicField across = GeodesicDistances(bridged, roots);
  EXPECT_NEAR(across.distance.back(), points.back().x(), 1e-6);

  options.max_gap_m = 0.05;
  const ScanGraph apart = BuildScanGraph(points, index, options);
  EXPECT_EQ(apart.bridges, 0);
  const GeodesicField cut = GeodesicDistances(apart, roots);
  EXPECT_TRUE(std::isinf(cut.distance.back()));
}

TEST(ScanGraph, NeverBridgesOutliers) {
  auto points = LineWithGap(0.01);
  points.push_back({0.2, 0.1, 0});  // a lone point 10 cm off the line
  const PointIndex index(points);
  const ScanGraph graph =
      BuildScanGraph(points, index, {.neighbour_radius_m = 0.015, .max_gap_m = 0.3});
  EXPECT_EQ(graph.pieces, 2);
  EXPECT_EQ(graph.bridges, 0);
}

}  // namespace
}  // namespace simtree::reconstruction
