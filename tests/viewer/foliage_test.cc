// Leaf placement: only on terminal branches, as many as the density asks, on the branch surface,
// deterministic for a seed, capped, and bad options refused.

#include "simtree/viewer/detail/foliage.h"

#include <gtest/gtest.h>

#include <set>

#include "simtree/core/error.h"
#include "viewer_fixtures.h"

namespace simtree::viewer {
namespace {

TEST(Foliage, LeavesGrowOnTerminalBranchesOnly) {
  const Tree tree = test::ViewerTree();
  FoliageOptions options;
  options.leaves_per_metre = 40;
  const auto leaves = PlaceLeaves(tree, 2.0f, options);
  const auto offsets = NodeOffsets(tree);
  ASSERT_EQ(offsets.back(), tree.NodeCount());
  std::set<int> branches;
  double expected = 0;
  for (const int b : {2, 3}) {  // branches 0 and 1 have children
    expected += 40 * tree.branches[b].Length() * (1 - options.start_fraction);
  }
  EXPECT_NEAR(static_cast<double>(leaves.size()), expected, 2.0);
  for (const LeafInstance& leaf : leaves) {
    branches.insert(leaf.branch);
    const Branch& b = tree.branches[leaf.branch];
    ASSERT_GE(leaf.node, offsets[b.id]);
    ASSERT_LT(leaf.node, offsets[b.id + 1]);
    // The leaf's base is on the branch surface near its node.
    const Eigen::Vector3d base =
        b.nodes[leaf.node - offsets[b.id]].position + leaf.offset.cast<double>();
    EXPECT_LT(leaf.offset.norm(), 0.2f);
    EXPECT_NEAR(leaf.orientation.norm(), 1.0f, 1e-5f);
    // Upper side turned to the sky.
    EXPECT_GT((leaf.orientation * Eigen::Vector3f::UnitZ()).z(), 0.0f);
    EXPECT_NEAR(leaf.scale, options.leaf_length_m / 2.0, options.leaf_length_m / 2.0 * 0.21);
    (void)base;
  }
  EXPECT_EQ(branches, (std::set<int>{2, 3}));
}

TEST(Foliage, SameSeedSameLeavesAndTheCapHolds) {
  const Tree tree = test::ViewerTree();
  FoliageOptions a;
  a.seed = 3;
  const auto first = PlaceLeaves(tree, 1.0f, a);
  const auto again = PlaceLeaves(tree, 1.0f, a);
  ASSERT_EQ(first.size(), again.size());
  for (size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].offset, again[i].offset);
  }
  FoliageOptions b = a;
  b.seed = 4;
  EXPECT_NE(PlaceLeaves(tree, 1.0f, b)[0].offset, first[0].offset);
  FoliageOptions capped = a;
  capped.leaves_per_metre = 1000;
  capped.max_leaves = 50;
  EXPECT_LE(PlaceLeaves(tree, 1.0f, capped).size(), 52u);
  FoliageOptions none = a;
  none.leaves_per_metre = 0;
  EXPECT_TRUE(PlaceLeaves(tree, 1.0f, none).empty());
}

TEST(Foliage, BadOptionsAreRefused) {
  const Tree tree = test::ViewerTree();
  FoliageOptions o;
  o.leaves_per_metre = -1;
  EXPECT_THROW(PlaceLeaves(tree, 1.0f, o), InputError);
  o = {};
  o.leaf_length_m = std::nan("");
  EXPECT_THROW(PlaceLeaves(tree, 1.0f, o), InputError);
  o = {};
  o.start_fraction = 1.0;
  EXPECT_THROW(PlaceLeaves(tree, 1.0f, o), InputError);
  EXPECT_THROW(PlaceLeaves(tree, 0.0f, {}), InputError);
}

TEST(Foliage, ValidateNamesTheBadField) {
  EXPECT_NO_THROW(FoliageOptions{}.Validate());
  const auto field = [](auto change) {
    FoliageOptions o;
    change(o);
    return test::InputErrorField([&] { o.Validate(); });
  };
  EXPECT_EQ(field([](FoliageOptions& o) { o.leaves_per_metre = INFINITY; }), "leaves_per_metre");
  EXPECT_EQ(field([](FoliageOptions& o) { o.leaf_length_m = 0; }), "leaf_length_m");
  EXPECT_EQ(field([](FoliageOptions& o) { o.start_fraction = -0.1; }), "start_fraction");
  EXPECT_EQ(field([](FoliageOptions& o) { o.tilt_rad = NAN; }), "tilt_rad");
  EXPECT_EQ(field([](FoliageOptions& o) { o.size_jitter = 1.5; }), "size_jitter");
  EXPECT_EQ(field([](FoliageOptions& o) { o.angle_jitter_rad = -1; }), "angle_jitter_rad");
  EXPECT_EQ(field([](FoliageOptions& o) { o.max_leaves = -1; }), "max_leaves");
}

}  // namespace
}  // namespace simtree::viewer
