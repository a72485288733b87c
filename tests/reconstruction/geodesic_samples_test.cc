#include "simtree/reconstruction/detail/geodesic_samples.h"

#include <gtest/gtest.h>

#include "reconstruction/reconstruction_fixtures.h"
#include "simtree/core/units.h"

namespace simtree::reconstruction {
namespace {

struct Sampled {
  std::vector<Eigen::Vector3d> points;
  GeodesicSampling sampling;
};

// A vertical trunk (radius 10 cm, 1 m) sampled every 1 cm, bands from its lowest ring.
Sampled SampleTrunk(const GeodesicSampleOptions& options, double gap_from = 0.0,
                    double gap_to = 0.0) {
  Sampled out;
  out.points = test::CylinderPoints({0, 0, 0}, {0, 0, 1}, 1.0, 0.1, 0.01, 0.0, 1, gap_from, gap_to);
  const PointIndex index(out.points);
  const ScanGraph graph = BuildScanGraph(out.points, index, {.neighbour_radius_m = 0.025});
  std::vector<int> roots;
  for (size_t i = 0; i < out.points.size(); ++i) {
    if (out.points[i].z() < 0.005) roots.push_back(static_cast<int>(i));
  }
  const GeodesicField field = GeodesicDistances(graph, roots);
  out.sampling = SampleGeodesicBands(out.points, graph, field, options);
  return out;
}

TEST(GeodesicSamples, RingsOfATrunkGiveSamplesOnItsAxis) {
  const Sampled s = SampleTrunk({.band_width_m = 0.05});
  ASSERT_GE(s.sampling.samples.size(), 18u);
  ASSERT_LE(s.sampling.samples.size(), 22u);
  for (const GeodesicSample& sample : s.sampling.samples) {
    if (sample.band >= 19) continue;  // the top rim: bands there are partial
    EXPECT_LT(sample.position.head<2>().norm(), 0.01) << "band " << sample.band;
    EXPECT_NEAR(sample.spread_m, 0.1, 0.02);
    if (sample.band > 0) {
      ASSERT_GE(sample.parent, 0);
      EXPECT_EQ(s.sampling.samples[sample.parent].band, sample.band - 1);
    }
  }
  EXPECT_EQ(s.sampling.unreached_points, 0u);
}

TEST(GeodesicSamples, ArcsOfARingBrokenByAGapAreMergedBackOntoTheAxis) {
  // A 90-degree strip hidden all the way up: every ring is a 270-degree arc, and a band that
  // starts on one side of the strip reaches the other side only around it.
  const Sampled merged = SampleTrunk({.band_width_m = 0.05}, 0.2 * kPi, 0.7 * kPi);
  for (const GeodesicSample& sample : merged.sampling.samples) {
    if (sample.band >= 19) continue;  // the top rim
    // The centroid of a 270-degree arc is 0.3 r off the axis: no worse than that.
    EXPECT_LT(sample.position.head<2>().norm(), 0.035);
  }
}

TEST(GeodesicSamples, UnreachedPointsHaveNoSample) {
  auto points = test::CylinderPoints({0, 0, 0}, {0, 0, 1}, 0.5, 0.05, 0.01);
  const size_t trunk = points.size();
  points.push_back({2, 2, 2});  // far from everything
  const PointIndex index(points);
  const ScanGraph graph = BuildScanGraph(points, index, {.neighbour_radius_m = 0.025});
  const std::vector<int> roots = {0};
  const GeodesicField field = GeodesicDistances(graph, roots);
  const GeodesicSampling sampling =
      SampleGeodesicBands(points, graph, field, {.band_width_m = 0.05});
  EXPECT_EQ(sampling.unreached_points, 1u);
  EXPECT_EQ(sampling.sample_of_point[trunk], -1);
}

}  // namespace
}  // namespace simtree::reconstruction
