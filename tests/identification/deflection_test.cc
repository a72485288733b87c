#include "simtree/identification/detail/deflection.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/identification/detail/test_signals.h"

namespace simtree::identification {
namespace {

using ::testing::HasSubstr;

// Root at the trunk, link 0 up-right from it, link 1 from link 0's end further out.
SyntheticMarkerTree TwoLinks() {
  SyntheticMarkerTree tree;
  tree.root_motion[0] = {{0.8, 0.02, 0.01, 0.0}};
  tree.links.resize(2);
  tree.links[0].rest_direction = Eigen::Vector3d(0.4, -1.0, 0.1);
  tree.links[0].length_m = 0.6;
  tree.links[0].theta_u = {{1.1, 0.03, 0.08, 0.0}};
  tree.links[0].theta_w = {{1.3, 0.04, 0.05, 0.5}};
  tree.links[1].parent = 0;
  tree.links[1].rest_direction = Eigen::Vector3d(1.0, -0.5, -0.2);
  tree.links[1].length_m = 0.4;
  tree.links[1].theta_u = {{1.7, 0.05, 0.1, 0.3}};
  tree.links[1].theta_w = {{2.1, 0.03, 0.06, 0.0}};
  return tree;
}

TEST(Deflection, LinksFollowTheMarkerList) {
  const std::vector<MarkerLink> markers = {
      {5, "T", 3, 7}, {3, "R", -1, 0}, {4, "B", 3, std::nullopt}};
  const std::vector<DeflectionLink> links = LinksFromMarkers(markers);
  ASSERT_EQ(links.size(), 3u);
  EXPECT_TRUE(links[0].is_root());
  EXPECT_EQ(links[0].child, 3);
  EXPECT_EQ(links[1].label, "R-T");
  EXPECT_EQ(links[1].grandparent, -1);
  EXPECT_EQ(*links[1].branch, 7);
  EXPECT_EQ(LinksFromMarkers(markers, false).size(), 2u);
}

TEST(Deflection, RecoversTheKnownAnglesOfEveryLinkWithTheParentSwingRemoved) {
  const SyntheticMarkerTree tree = TwoLinks();
  std::vector<MarkerLink> markers;
  const Trajectories t = MakeMarkerTrajectories(tree, 30.0, 0.0, 10.0, &markers);
  const std::vector<DeflectionSignal> signals =
      ComputeDeflectionSignals(t, LinksFromMarkers(markers), 0, -1);
  ASSERT_EQ(signals.size(), 3u);
  EXPECT_EQ(signals[0].kind, DeflectionKind::kDisplacement);
  for (int k = 0; k < 2; ++k) {
    const DeflectionSignal& d = signals[k + 1];
    ASSERT_TRUE(d.ok()) << d.problem;
    EXPECT_EQ(d.kind, DeflectionKind::kRelativeAngle);
    EXPECT_NEAR(d.rest_length_m, tree.links[k].length_m, 0.01);
    ASSERT_EQ(d.signal.size(), 300);
    // The rest is estimated from the decay's tail, so compare after removing the mean offset.
    for (int c = 0; c < 2; ++c) {
      const auto& modes = c == 0 ? tree.links[k].theta_u : tree.links[k].theta_w;
      double offset = 0;
      for (int i = 0; i < 300; ++i) offset += (d.signal.values(i, c) - modes[0](i / 30.0)) / 300;
      EXPECT_LT(std::abs(offset), 0.01);
      for (int i = 0; i < 300; i += 7) {
        EXPECT_NEAR(d.signal.values(i, c) - offset, modes[0](i / 30.0), 2e-3)
            << "link " << k << " channel " << c << " sample " << i;
      }
    }
  }
  // The root's displacement is mostly along x (its only motion).
  EXPECT_GT(std::abs(signals[0].u.x()), 0.99);
}

TEST(Deflection, MissingMarkersAndEmptyRecordsAreProblemsNotCrashes) {
  std::vector<MarkerLink> markers;
  const Trajectories t = MakeMarkerTrajectories(TwoLinks(), 30.0, 0.0, 2.0, &markers);
  markers.push_back({9, "M9", 2, std::nullopt});
  const std::vector<DeflectionSignal> signals =
      ComputeDeflectionSignals(t, LinksFromMarkers(markers), 0, -1);
  ASSERT_EQ(signals.size(), 4u);
  EXPECT_EQ(signals[3].status, DeflectionStatus::kMissingTrajectory);
  EXPECT_THAT(signals[3].problem, HasSubstr("marker 9 has no trajectory"));
  EXPECT_EQ(signals[3].signal.size(), 0);
  // A link whose grandparent is missing cannot undo the parent's swing either.
  markers.push_back({10, "M10", 9, std::nullopt});
  EXPECT_EQ(ComputeDeflectionSignals(t, LinksFromMarkers(markers), 0, -1)[4].status,
            DeflectionStatus::kMissingTrajectory);
  EXPECT_EQ(ComputeDeflectionSignals(t, LinksFromMarkers(markers), 5, 6)[1].status,
            DeflectionStatus::kTooFewFrames);
}

TEST(Deflection, InvalidFramesOfAnyMarkerOfTheLinkAreGaps) {
  std::vector<MarkerLink> markers;
  Trajectories t = MakeMarkerTrajectories(TwoLinks(), 30.0, 0.0, 4.0, &markers);
  t.tracks[1].valid[10] = false;  // marker 1: parent of link 2, child of link 1
  t.tracks[0].valid[20] = false;  // the root: grandparent of link 2
  const std::vector<DeflectionSignal> s =
      ComputeDeflectionSignals(t, LinksFromMarkers(markers), 0, -1);
  EXPECT_FALSE(s[1].signal.valid[10]);
  EXPECT_FALSE(s[1].signal.valid[20]);
  EXPECT_FALSE(s[2].signal.valid[10]);
  EXPECT_FALSE(s[2].signal.valid[20]);
  EXPECT_TRUE(s[2].signal.valid[11]);
  EXPECT_TRUE(std::isnan(s[2].signal.values(10, 0)));
}

}  // namespace
}  // namespace simtree::identification
