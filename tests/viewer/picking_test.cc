// Picking: the ray under a pixel finds the branch drawn there, with its arc length, the nearest
// of two in line, nothing in empty sky; a wrong node count is refused.

#include "simtree/viewer/detail/picking.h"

#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "viewer_fixtures.h"

namespace simtree::viewer {
namespace {

std::vector<Eigen::Vector3f> RestNodes(const Tree& tree) {
  std::vector<Eigen::Vector3f> nodes;
  for (const Branch& b : tree.branches) {
    for (const Node& n : b.nodes) nodes.push_back(n.position.cast<float>());
  }
  return nodes;
}

TEST(Picking, FindsTheBranchUnderThePixel) {
  const Tree tree = test::ViewerTree();
  const auto nodes = RestNodes(tree);
  OrbitCamera orbit;  // in front of the tree, looking along +Y
  orbit.target = {0, 0, 0.5};
  orbit.pitch_rad = 0;
  orbit.distance_m = 3;
  const CameraView view = orbit.View(640, 480);
  // The trunk at 0.3 m height.
  const auto pixel = view.Project({0, 0, 0.3});
  ASSERT_TRUE(pixel.has_value());
  const auto hit = PickBranch(tree, nodes, view, view.PixelRay(pixel->x(), pixel->y()));
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->branch, 0);
  EXPECT_NEAR(hit->arc_length, 0.3, 0.01);
  EXPECT_NEAR(hit->ray_distance, 3.0 - 0.088, 0.03);  // about the trunk's near surface
  // Branch 1's tip.
  const Eigen::Vector3d tip = tree.branches[1].tip().position;
  const auto tip_pixel = view.Project(tip);
  const auto tip_hit = PickBranch(tree, nodes, view, view.PixelRay(tip_pixel->x(), tip_pixel->y()));
  ASSERT_TRUE(tip_hit.has_value());
  EXPECT_TRUE(tip_hit->branch == 1 || tip_hit->branch == 3);
  // Sky.
  EXPECT_FALSE(PickBranch(tree, nodes, view, view.PixelRay(5, 5)).has_value());
}

TEST(Picking, TheNearestOfTwoInLineWins) {
  Tree tree;
  for (int i = 0; i < 2; ++i) {
    Branch b;
    b.id = i;
    b.parent = i - 1;
    const double y = i == 0 ? 1.0 : -1.0;  // branch 1 is nearer the camera at y = -5
    b.nodes = {{{0, y, 0}, 0.05}, {{0, y, 1}, 0.05}};
    tree.branches.push_back(b);
  }
  const auto nodes = RestNodes(tree);
  OrbitCamera orbit;
  orbit.target = {0, 0, 0.5};
  orbit.pitch_rad = 0;
  orbit.distance_m = 5;
  const CameraView view = orbit.View(400, 400);
  const auto hit = PickBranch(tree, nodes, view, view.PixelRay(200, 200));
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->branch, 1);
  EXPECT_NEAR(hit->arc_length, 0.5, 1e-6);
  EXPECT_THROW(PickBranch(tree, std::span(nodes).first(3), view, view.PixelRay(200, 200)),
               InputError);
}

TEST(Picking, ThinTwigsAreCaughtWithinAFewPixels) {
  Tree tree;
  Branch b;
  b.nodes = {{{0, 0, 0}, 1e-4}, {{0, 0, 1}, 1e-4}};
  tree.branches.push_back(b);
  const auto nodes = RestNodes(tree);
  OrbitCamera orbit;
  orbit.target = {0, 0, 0.5};
  orbit.pitch_rad = 0;
  orbit.distance_m = 5;
  const CameraView view = orbit.View(400, 400);
  EXPECT_TRUE(PickBranch(tree, nodes, view, view.PixelRay(202, 200)).has_value());
  EXPECT_FALSE(PickBranch(tree, nodes, view, view.PixelRay(215, 200)).has_value());
}

TEST(Picking, ValidateNamesTheBadField) {
  EXPECT_NO_THROW(PickOptions{}.Validate());
  EXPECT_EQ(test::InputErrorField([] { PickOptions{.min_radius_px = -1}.Validate(); }),
            "min_radius_px");
  EXPECT_EQ(test::InputErrorField([] { PickOptions{.min_radius_px = NAN}.Validate(); }),
            "min_radius_px");
}

}  // namespace
}  // namespace simtree::viewer
