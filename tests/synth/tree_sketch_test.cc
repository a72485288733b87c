#include "simtree/synth/detail/tree_sketch.h"

#include <gtest/gtest.h>

#include "core/tree_fixtures.h"

namespace simtree::synth {
namespace {

bool IsBackground(const RgbImage& image, int x, int y) {
  return image.at(x, y, 0) == 236 && image.at(x, y, 1) == 241 && image.at(x, y, 2) == 246;
}

TEST(TreeSketch, DrawsThreeViewsOfTheTree) {
  const Tree tree = test::SmallTreeWithMaterials();
  TreeSketchOptions options;
  options.view_height_px = 300;
  const RgbImage image = SketchTree(tree, options);
  ASSERT_EQ(image.height, 300);
  // One scale for all views: 300 px for the height from the ground (or the lowest radius) to
  // the top, with 0.15 m of margin on both sides.
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  const double scale = 300 / (hi.z() - std::min(lo.z(), 0.0) + 2 * 0.15);
  // Front view: the trunk's centre column half-way up is drawn, the far left corner is sky.
  const int trunk_x = static_cast<int>((0.0 - lo.x() + 0.15) * scale);
  EXPECT_FALSE(IsBackground(image, trunk_x, 150));
  EXPECT_TRUE(IsBackground(image, 1, 1));
  // The markers are red dots.
  const Eigen::Vector3d m = tree.markers[0].position;
  const int mx = static_cast<int>((m.x() - lo.x() + 0.15) * scale);
  const int my = static_cast<int>((hi.z() + 0.15 - m.z()) * scale);
  EXPECT_EQ(image.at(mx, my, 0), 220);
  EXPECT_EQ(image.at(mx, my, 1), 20);
  // Three panels side by side: wider than the front view alone.
  EXPECT_GT(image.width, static_cast<int>((hi.x() - lo.x() + 0.3) * scale) * 2);
}

TEST(TreeSketch, EmptyTreeGivesATinyImage) {
  const RgbImage image = SketchTree(Tree{});
  EXPECT_EQ(image.width, 1);
  EXPECT_EQ(image.height, 1);
}

}  // namespace
}  // namespace simtree::synth
