#include "simtree/reconstruction/detail/scene_cleanup.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "reconstruction/reconstruction_fixtures.h"

namespace simtree::reconstruction {
namespace {

GroundPlane FlatGround() {
  GroundPlane ground;
  ground.found = true;
  ground.clearance_m = 0.01;
  return ground;
}

TEST(SceneCleanup, SparseReturnsAreFlaggedAndSurfacesKept) {
  auto points = test::CylinderPoints({0, 0, 0}, {0, 0, 1}, 1.0, 0.05, 0.005);
  const size_t surface = points.size();
  // Stray returns, each more than 10 cm from anything.
  for (int i = 0; i < 20; ++i) points.push_back({0.5 + 0.2 * i, 0.3, 0.1 * (i % 5)});
  const std::vector<char> sparse = FindSparseReturns(points, {.radius_m = 0.02});
  EXPECT_EQ(std::count(sparse.begin(), sparse.begin() + surface, 1), 0);
  EXPECT_EQ(std::count(sparse.begin() + surface, sparse.end(), 1), 20);
  EXPECT_TRUE(FindSparseReturns(std::vector<Eigen::Vector3d>{}).empty());
}

TEST(SceneCleanup, ObjectsOnTheGroundApartFromTheTreeAreFlagged) {
  // The tree: a trunk with a branch; a post standing 1 m away; a branch piece hidden from the
  // trunk by a gap (not on the ground: it stays).
  auto tree = test::CylinderPoints({0, 0, 0}, {0, 0, 1}, 2.0, 0.05, 0.01);
  const auto post = test::CylinderPoints({1, 0, 0}, {0, 0, 1}, 0.5, 0.03, 0.01);
  const auto floating = test::CylinderPoints({0.3, 0, 1.5}, {1, 0, 0}, 0.3, 0.02, 0.01);
  std::vector<Eigen::Vector3d> points = tree;
  points.insert(points.end(), post.begin(), post.end());
  points.insert(points.end(), floating.begin(), floating.end());
  GroundObjectOptions options;
  options.neighbour_radius_m = 0.03;
  options.touch_height_m = 0.03;
  const std::vector<char> object = FindObjectsOnGround(points, FlatGround(), options);
  const auto begin = object.begin();
  EXPECT_EQ(std::count(begin, begin + tree.size(), 1), 0);
  EXPECT_EQ(std::count(begin + tree.size(), begin + tree.size() + post.size(), 1),
            static_cast<long>(post.size()));
  EXPECT_EQ(std::count(begin + tree.size() + post.size(), object.end(), 1), 0);
  // Without ground nothing is an object.
  const std::vector<char> none = FindObjectsOnGround(points, GroundPlane{}, options);
  EXPECT_EQ(std::count(none.begin(), none.end(), 1), 0);
}

}  // namespace
}  // namespace simtree::reconstruction
