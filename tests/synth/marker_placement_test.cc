#include "simtree/synth/detail/marker_placement.h"

#include <algorithm>
#include <set>

#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/core/tree_json.h"
#include "simtree/synth/detail/tree_generator.h"
#include "simtree/synth/species.h"
#include "test_util.h"

namespace simtree::synth {
namespace {

const Eigen::Vector3d kCamera(0.0, -2.5, 1.4);

// True when `ancestor` is `branch` or one of its ancestors.
bool IsAncestor(const Tree& tree, int ancestor, int branch) {
  for (int b = branch; b >= 0; b = tree.branches[b].parent) {
    if (b == ancestor) return true;
  }
  return false;
}

class Markers : public ::testing::TestWithParam<std::string> {};

TEST_P(Markers, EveryLevelIsTapedAndLinkedDownToTheTrunk) {
  for (const uint64_t seed : {1, 2, 3}) {
    Tree tree = GenerateTree(SpeciesPreset(GetParam()), seed);
    const MarkerPlacementResult result = PlaceMarkers(
        tree, MarkerPlacementOptions{.count = 12, .camera_position = kCamera, .seed = seed});
    SCOPED_TRACE(GetParam() + " seed " + std::to_string(seed));
    ASSERT_EQ(tree.markers.size(), 12u);
    EXPECT_GT(result.sites, 12);
    // The root on the trunk, below every branch; ids in order; labels.
    const auto children = tree.Children();
    const Marker& root = tree.markers[0];
    EXPECT_EQ(root.branch, 0);
    EXPECT_EQ(root.parent, -1);
    for (const int c : children[0]) {
      EXPECT_LT(root.arc_length, tree.trunk().ArcLengths()[tree.branches[c].parent_node]);
    }
    std::set<int> branches;
    std::vector<int> per_level(tree.MaxLevel() + 1, 0);
    for (size_t i = 0; i < tree.markers.size(); ++i) {
      const Marker& m = tree.markers[i];
      EXPECT_EQ(m.id, static_cast<int>(i));
      // Appended, not "M" + ...: there GCC 12 warns falsely of a string overflow.
      EXPECT_EQ(m.label, std::string("M").append(std::to_string(i)));
      EXPECT_LT((m.position - tree.branches[m.branch].PointAt(m.arc_length)).norm(), 1e-9);
      EXPECT_TRUE(branches.insert(m.branch).second) << "two markers on branch " << m.branch;
      ++per_level[tree.branches[m.branch].level];
      // Tape needs a branch thick enough, away from the forks.
      const auto arcs = tree.branches[m.branch].ArcLengths();
      const size_t node = std::find(arcs.begin(), arcs.end(), m.arc_length) - arcs.begin();
      ASSERT_LT(node, arcs.size()) << "markers sit on nodes";
      EXPECT_GE(tree.branches[m.branch].nodes[node].radius, 0.003);
      EXPECT_GE(m.arc_length, 0.05);
      EXPECT_GE(arcs.back() - m.arc_length, 0.05);
      for (const int c : children[m.branch]) {
        EXPECT_GE(std::abs(arcs[tree.branches[c].parent_node] - m.arc_length), 0.05 - 1e-12);
      }
      if (i == 0) continue;
      // Linked to an earlier marker on the way down to the trunk: no cycles.
      ASSERT_GE(m.parent, 0);
      ASSERT_LT(m.parent, m.id);
      const Marker& parent = tree.markers[m.parent];
      EXPECT_TRUE(IsAncestor(tree, parent.branch, m.branch));
      if (parent.branch == m.branch) {
        EXPECT_LT(parent.arc_length, m.arc_length);
      }
    }
    EXPECT_EQ(per_level, result.markers_per_level);
    // Every level down to 4 is taped (the paper: "markers were attached to each level").
    for (int level = 0; level <= std::min(4, tree.MaxLevel()); ++level) {
      EXPECT_GE(per_level[level], 1) << "level " << level;
    }
    // Most markers face the camera.
    EXPECT_LE(result.hidden, 3);
    // The file writer accepts the links.
    EXPECT_NO_THROW(TreeToJson(tree));
  }
}

INSTANTIATE_TEST_SUITE_P(Synth, Markers, ::testing::ValuesIn(SpeciesPresetNames()));

TEST(MarkerPlacement, PrefersTheCameraSide) {
  const Tree grown = GenerateTree(SpeciesPreset("acer_rubrum"), 4);
  double mean_y[2] = {0, 0};
  int k = 0;
  for (const double side : {-1.0, 1.0}) {
    Tree tree = grown;
    PlaceMarkers(
        tree, MarkerPlacementOptions{
                  .count = 12, .camera_position = Eigen::Vector3d(0, 2.5 * side, 1.4), .seed = 1});
    for (const Marker& m : tree.markers) mean_y[k] += m.position.y() / tree.markers.size();
    ++k;
  }
  EXPECT_LT(mean_y[0], mean_y[1] - 0.1);
}

TEST(MarkerPlacement, DeterministicBySeedAndCountIsHonoured) {
  const Tree grown = GenerateTree(SpeciesPreset("acer_palmatum"), 2);
  Tree a = grown, b = grown, c = grown;
  PlaceMarkers(a, MarkerPlacementOptions{.count = 9, .seed = 5});
  PlaceMarkers(b, MarkerPlacementOptions{.count = 9, .seed = 5});
  PlaceMarkers(c, MarkerPlacementOptions{.count = 15, .seed = 5});
  ASSERT_EQ(a.markers.size(), 9u);
  EXPECT_EQ(TreeToJson(a).dump(), TreeToJson(b).dump());
  EXPECT_EQ(c.markers.size(), 15u);
  // Placing again replaces the markers.
  PlaceMarkers(c, MarkerPlacementOptions{.count = 3, .seed = 5});
  EXPECT_EQ(c.markers.size(), 3u);
}

TEST(MarkerPlacement, FirstChainRunsDownTheGivenBranch) {
  const Tree grown = GenerateTree(SpeciesPreset("acer_rubrum"), 3);
  const auto children = grown.Children();
  int tried = 0;
  for (const int start : children[0]) {
    // Level-1 branches with a child plainly thick and long enough for tape, forking well out.
    const Branch& parent = grown.branches[start];
    const bool tapeable_child =
        std::any_of(children[start].begin(), children[start].end(), [&](int c) {
          const Branch& child = grown.branches[c];
          return child.nodes.front().radius >= 0.006 && child.Length() >= 0.4 &&
                 parent.ArcLengths()[child.parent_node] >= 0.25;
        });
    if (parent.level != 1 || !tapeable_child) continue;
    if (++tried > 3) break;
    Tree tree = grown;
    PlaceMarkers(tree, MarkerPlacementOptions{.count = 12, .first_chain_branch = start});
    int on_branch = 0, below = 0;
    for (const Marker& m : tree.markers) {
      on_branch += m.branch == start;
      below += m.branch != start && IsAncestor(tree, start, m.branch);
    }
    SCOPED_TRACE("first chain on branch " + std::to_string(start));
    EXPECT_EQ(on_branch, 1);
    EXPECT_GE(below, 1);  // the chain goes on into its children
  }
  EXPECT_GE(tried, 2);
}

TEST(MarkerPlacement, ExcludedSitesAreNotUsed) {
  Tree tree = GenerateTree(SpeciesPreset("magnolia"), 2);
  PlaceMarkers(tree, MarkerPlacementOptions{.count = 12});
  MarkerPlacementOptions again{.count = 12};
  for (const Marker& m : tree.markers) again.excluded_sites.emplace_back(m.branch, m.arc_length);
  const std::vector<Marker> first = tree.markers;
  PlaceMarkers(tree, again);
  ASSERT_EQ(tree.markers.size(), 12u);
  for (const Marker& m : tree.markers) {
    for (const Marker& old : first) {
      if (old.branch == m.branch) {
        EXPECT_GE(std::abs(old.arc_length - m.arc_length), 0.1 - 1e-9);
      }
    }
  }
}

TEST(MarkerPlacement, BadInputsAreRefused) {
  Tree tree = GenerateTree(SpeciesPreset("magnolia"), 1);
  EXPECT_THROW(PlaceMarkers(tree, MarkerPlacementOptions{.count = 0}), InputError);
  EXPECT_THROW(PlaceMarkers(tree, MarkerPlacementOptions{.min_radius_m = 0}), InputError);
  // No trunk site thick enough: named, nothing placed.
  EXPECT_THROW(PlaceMarkers(tree, MarkerPlacementOptions{.min_radius_m = 0.5}), InputError);
  Tree empty;
  EXPECT_THROW(PlaceMarkers(empty), InputError);
}

}  // namespace
}  // namespace simtree::synth
