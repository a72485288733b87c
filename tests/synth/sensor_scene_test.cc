#include "simtree/synth/detail/sensor_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "core/tree_fixtures.h"
#include "simtree/core/error.h"
#include "synth/sensor_fixtures.h"

namespace simtree::synth {
namespace {

const Eigen::Vector3d kNaN(std::numeric_limits<double>::quiet_NaN(), 0, 0);

TEST(SensorScene, ARayHitsAKnownCylinderWhereGeometrySaysWithItsBranchAndArcLength) {
  const Tree tree = test::VerticalCylinder(0, 0, 2.0, 0.05);
  const SensorScene scene(tree, test::BareScene());
  // From x = 2 towards the axis at heights along the trunk.
  for (double z : {0.15, 0.77, 1.5, 1.93}) {
    const SceneHit hit = scene.Intersect({2.0, 0.0, z}, {-1.0, 0.0, 0.0});
    ASSERT_EQ(hit.kind, SurfaceKind::kBranch) << z;
    EXPECT_EQ(hit.object, SceneObject::kTree);
    EXPECT_EQ(hit.branch, 0);
    EXPECT_NEAR(hit.t, 2.0 - 0.05, 1e-6) << z;  // refined onto the true surface
    EXPECT_NEAR(hit.arc_length, z, 1e-4);
    EXPECT_NEAR(hit.radius, 0.05, 1e-9);
    EXPECT_NEAR(hit.normal.x(), 1.0, 1e-3);  // the true cylinder's normal, facing the ray
    EXPECT_EQ(hit.marker, -1);
  }
  // Off to the side by 0.03 m: the cylinder at x = sqrt(r^2 - 0.03^2).
  const SceneHit side = scene.Intersect({2.0, 0.03, 1.0}, {-1.0, 0.0, 0.0});
  ASSERT_TRUE(side.hit());
  EXPECT_NEAR(side.t, 2.0 - std::sqrt(0.05 * 0.05 - 0.03 * 0.03), 1e-6);
  EXPECT_NEAR(side.normal.y(), 0.6, 5e-3);
  // Past the top and beside it: nothing.
  EXPECT_FALSE(scene.Intersect({2.0, 0.0, 2.2}, {-1.0, 0.0, 0.0}).hit());
  EXPECT_FALSE(scene.Intersect({2.0, 0.06, 1.0}, {-1.0, 0.0, 0.0}).hit());
  // A ray that stops short does not reach it.
  EXPECT_FALSE(scene.Intersect({2.0, 0.0, 1.0}, {-1.0, 0.0, 0.0}, 0.0, 1.9).hit());
  EXPECT_TRUE(scene.Occluded({2.0, 0.0, 1.0}, {-1.0, 0.0, 0.0}, 0.0, 10.0));
  EXPECT_FALSE(scene.Occluded({2.0, 0.0, 1.0}, {1.0, 0.0, 0.0}, 0.0, 10.0));
}

TEST(SensorScene, CoherentTracingGivesTheSameHitsAsSingleRays) {
  const Tree tree = test::Tree02();
  const SensorScene scene(tree, DefaultSceneOptions(tree, 3));
  const Eigen::Vector3d origin(3.0, 0.5, 1.5);
  std::vector<Eigen::Vector3d> directions;
  for (int i = 0; i < 500; ++i) {
    directions.emplace_back(-1.0, 0.4 * std::sin(0.37 * i), 0.5 * std::cos(0.23 * i));
  }
  std::vector<SceneHit> hits(directions.size());
  scene.IntersectCoherent(origin, directions, hits);
  int tree_hits = 0;
  for (size_t i = 0; i < directions.size(); ++i) {
    const SceneHit one = scene.Intersect(origin, directions[i]);
    ASSERT_EQ(one.kind, hits[i].kind) << i;
    EXPECT_NEAR(one.t, hits[i].t, 1e-5) << i;
    EXPECT_EQ(one.branch, hits[i].branch) << i;
    tree_hits += one.kind == SurfaceKind::kBranch;
  }
  EXPECT_GT(tree_hits, 20);
  std::vector<Eigen::Vector3d> origins;
  for (const SceneHit& h : hits) origins.push_back(h.point + 1e-4 * h.normal);
  std::vector<uint8_t> occluded(origins.size());
  const Eigen::Vector3d sun = scene.options().sun_direction.normalized();
  scene.OccludedCoherent(origins, sun, 1e-4, 1e3, occluded);
  for (size_t i = 0; i < origins.size(); ++i) {
    EXPECT_EQ(occluded[i] != 0, scene.Occluded(origins[i], sun, 1e-4, 1e3)) << i;
  }
}

TEST(SensorScene, TapeBandsLabelTheHitsAtTheMarkersArcLength) {
  Tree tree = test::VerticalCylinder(0, 0, 2.0, 0.05);
  tree.markers.push_back({0, "M0", 0, 1.0, -1, {0, 0, 1.0}});
  const SensorScene scene(tree, test::BareScene());
  ASSERT_EQ(scene.marker_bands().size(), 1u);
  EXPECT_NEAR(scene.marker_bands()[0].begin, 0.98, 1e-12);
  EXPECT_NEAR(scene.marker_bands()[0].end, 1.02, 1e-12);
  EXPECT_EQ(scene.Intersect({2.0, 0.0, 1.01}, {-1.0, 0.0, 0.0}).marker, 0);
  EXPECT_EQ(scene.Intersect({2.0, 0.0, 0.99}, {-1.0, 0.0, 0.0}).marker, 0);
  EXPECT_EQ(scene.Intersect({2.0, 0.0, 1.03}, {-1.0, 0.0, 0.0}).marker, -1);
  EXPECT_EQ(scene.Intersect({2.0, 0.0, 0.5}, {-1.0, 0.0, 0.0}).marker, -1);
  // The band alone: hit where the tape is, missed elsewhere on the branch.
  EXPECT_TRUE(scene.IntersectMarkerBand(0, {2.0, 0.0, 1.0}, {-1.0, 0.0, 0.0}).hit());
  EXPECT_FALSE(scene.IntersectMarkerBand(0, {2.0, 0.0, 1.5}, {-1.0, 0.0, 0.0}).hit());
  EXPECT_FALSE(scene.IntersectMarkerBand(1, {2.0, 0.0, 1.0}, {-1.0, 0.0, 0.0}).hit());
  // Markers off: no bands.
  SceneOptions off = test::BareScene();
  off.markers = false;
  const SensorScene plain(tree, off);
  EXPECT_TRUE(plain.marker_bands().empty());
  EXPECT_EQ(plain.Intersect({2.0, 0.0, 1.0}, {-1.0, 0.0, 0.0}).marker, -1);
}

TEST(SensorScene, SetPoseMovesTheBranchesAndTheirTape) {
  Tree tree = test::VerticalCylinder(0, 0, 2.0, 0.05);
  tree.markers.push_back({0, "M0", 0, 1.0, -1, {0, 0, 1.0}});
  SensorScene scene(tree, test::BareScene());
  TreePose pose(tree);
  for (int i = 0; i < pose.node_count(0); ++i) pose.node(0, i) += Eigen::Vector3d(0.3, 0.2, 0.1);
  scene.SetPose(pose);
  EXPECT_FALSE(scene.Intersect({2.0, 0.0, 1.0}, {-1.0, 0.0, 0.0}).hit());
  const SceneHit hit = scene.Intersect({2.0, 0.2, 1.1}, {-1.0, 0.0, 0.0});
  ASSERT_TRUE(hit.hit());
  EXPECT_NEAR(hit.t, 2.0 - 0.3 - 0.05, 1e-6);
  EXPECT_NEAR(hit.arc_length, 1.0, 1e-4);  // rest arc length
  EXPECT_EQ(hit.marker, 0);
  EXPECT_TRUE(scene.IntersectMarkerBand(0, {2.0, 0.2, 1.1}, {-1.0, 0.0, 0.0}).hit());
}

TEST(SensorScene, GroundHedgeObjectsAndRopeAreWhatTheyAre) {
  const Tree tree = test::VerticalCylinder(0, 0, 2.0, 0.05);
  SceneOptions o;
  o.hedge_radius_m = 8.0;
  o.boxes.push_back({.center = {1.0, 1.0, 0.2}, .half_extent = {0.2, 0.2, 0.2}});
  o.posts.push_back({.base = {-1.0, 1.0}, .radius_m = 0.05, .height_m = 1.5});
  o.shrubs.push_back({.center = {0.0, -1.5, 0.3}, .radius_m = 0.4, .twigs = 200, .seed = 4});
  SensorScene scene(tree, o);
  const SceneHit ground = scene.Intersect({0.5, 0.5, 1.0}, {0.0, 0.0, -1.0});
  EXPECT_EQ(ground.kind, SurfaceKind::kGround);
  EXPECT_NEAR(ground.t, 1.0, 1e-6);
  EXPECT_NEAR(ground.normal.z(), 1.0, 1e-9);
  const SceneHit hedge = scene.Intersect({0.0, 0.5, 1.0}, {1.0, 0.0, 0.0});
  EXPECT_EQ(hedge.kind, SurfaceKind::kBackground);
  EXPECT_EQ(hedge.object, SceneObject::kHedge);
  EXPECT_NEAR(hedge.t, 8.0, 0.5);
  const SceneHit box = scene.Intersect({1.0, 1.0, 2.0}, {0.0, 0.0, -1.0});
  EXPECT_EQ(box.object, SceneObject::kBox);
  EXPECT_EQ(box.object_index, 0);
  EXPECT_NEAR(box.t, 1.6, 1e-5);
  const SceneHit post = scene.Intersect({-1.0, 3.0, 1.0}, {0.0, -1.0, 0.0});
  EXPECT_EQ(post.kind, SurfaceKind::kOccluder);
  EXPECT_EQ(post.object, SceneObject::kPost);
  EXPECT_NEAR(post.t, 2.0 - 0.05, 1e-4);
  EXPECT_NEAR(post.radius, 0.05, 1e-6);
  int shrub = 0;
  for (int i = 0; i < 50; ++i) {
    const SceneHit h = scene.Intersect({2.0, -1.5 + 0.01 * (i - 25), 0.4}, {-1.0, 0.0, 0.0});
    shrub += h.object == SceneObject::kShrub;
  }
  EXPECT_GT(shrub, 3);
  // No rope until there is one; then it runs from the tree to the anchor.
  EXPECT_FALSE(scene.Intersect({1.0, -0.5, 0.5}, {0.0, 1.0, 0.0}).kind == SurfaceKind::kRope);
  scene.SetRope(RopeSegment{.branch = 0, .arc_length = 1.0, .anchor = {2.0, 0.0, 0.0}});
  const SceneHit rope = scene.Intersect({1.0, -0.5, 0.5}, {0.0, 1.0, 0.0});
  EXPECT_EQ(rope.kind, SurfaceKind::kRope);
  EXPECT_NEAR(rope.t, 0.5 - 0.004, 1e-4);
  EXPECT_NEAR(rope.along, std::sqrt(1.25), 2e-3);  // from (0, 0, 1) to (1, 0, 0.5)
  scene.SetRope(std::nullopt);
  EXPECT_NE(scene.Intersect({1.0, -0.5, 0.5}, {0.0, 1.0, 0.0}).kind, SurfaceKind::kRope);
}

TEST(SensorScene, DefaultOptionsPutTheHedgeBeyondReachAndObjectsNearTheTrunk) {
  const Tree tree = test::Tree02();
  const SceneOptions a = DefaultSceneOptions(tree, 1);
  const SceneOptions b = DefaultSceneOptions(tree, 1);
  const SceneOptions hard = DefaultSceneOptions(tree, 1, true);
  EXPECT_GE(a.hedge_radius_m, 8.0);
  EXPECT_EQ(a.boxes.size(), 3u);
  EXPECT_TRUE(a.posts.empty());
  EXPECT_TRUE(a.shrubs.empty());
  EXPECT_EQ(hard.posts.size(), 1u);
  EXPECT_EQ(hard.shrubs.size(), 1u);
  for (size_t i = 0; i < a.boxes.size(); ++i) {
    EXPECT_EQ(a.boxes[i].center, b.boxes[i].center);  // deterministic
    const double d = (a.boxes[i].center.head<2>() - tree.trunk().base().position.head<2>()).norm();
    EXPECT_GT(d, 0.6);
    EXPECT_LT(d, 1.8);
  }
  EXPECT_GT(a.sun_direction.z(), 0.3);
  EXPECT_NE(DefaultSceneOptions(tree, 2).sun_direction, a.sun_direction);
}

TEST(SensorScene, RefusesBadInput) {
  const Tree tree = test::SmallTree();
  SensorScene scene(tree, test::BareScene());
  // A pose with NaN.
  TreePose nan_pose(tree);
  nan_pose.node(1, 2) = kNaN;
  EXPECT_THROW(scene.SetPose(nan_pose), InputError);
  // A pose of another tree (different branch or node counts).
  EXPECT_THROW(scene.SetPose(TreePose(test::VerticalCylinder(0, 0, 1, 0.1))), InputError);
  Tree longer = tree;
  longer.branches[2].nodes.push_back(longer.branches[2].nodes.back());
  longer.branches[2].nodes.back().position.z() += 0.1;
  EXPECT_THROW(scene.SetPose(TreePose(longer)), InputError);
  // The scene keeps its old pose after a refused one.
  EXPECT_EQ(scene.pose().node(1, 2), tree.branches[1].nodes[2].position);
  // A rope on a branch that does not exist, or with NaN.
  EXPECT_THROW(scene.SetRope(RopeSegment{.branch = 9}), InputError);
  EXPECT_THROW(scene.SetRope(RopeSegment{.branch = 1, .arc_length = 0.1, .anchor = kNaN}),
               InputError);
  // Options.
  SceneOptions o = test::BareScene();
  o.tape_width_m = 0.0;
  EXPECT_THROW(SensorScene(tree, o), InputError);
  o = test::BareScene();
  o.sun_direction = Eigen::Vector3d::Zero();
  EXPECT_THROW(SensorScene(tree, o), InputError);
  o = test::BareScene();
  o.boxes.push_back({.half_extent = {0.1, -0.1, 0.1}});
  EXPECT_THROW(SensorScene(tree, o), InputError);
  // An empty tree, a marker on a missing branch.
  EXPECT_THROW(SensorScene(Tree{}, o), InputError);
  Tree bad_marker = tree;
  bad_marker.markers.push_back({0, "M0", 17, 0.1, -1, {0, 0, 0}});
  EXPECT_THROW(SensorScene(bad_marker, test::BareScene()), InputError);
}

}  // namespace
}  // namespace simtree::synth
