#include "simtree/identification/marker_assignment.h"

#include <gtest/gtest.h>

#include "tree_fixture.h"

namespace simtree::identification {
namespace {

TEST(MarkerAssignment, MarkersLandOnTheirBranchesAndLinkDownTheHierarchy) {
  const Tree tree = test::IdentificationTree();
  // A camera 3 m in front of the tree looking at it (OpenCV axes: x right, y down, z forward).
  Eigen::Isometry3d world_from_camera = Eigen::Isometry3d::Identity();
  Eigen::Matrix3d r;
  r.col(0) = Eigen::Vector3d(1, 0, 0);   // camera x -> world x
  r.col(1) = Eigen::Vector3d(0, 0, -1);  // camera y (down) -> world -z
  r.col(2) = Eigen::Vector3d(0, 1, 0);   // camera z (forward) -> world y
  world_from_camera.linear() = r;
  world_from_camera.translation() = Eigen::Vector3d(0, -3, 1);
  // Markers on the bark: trunk at 0.8 m, branch 1 at 0.3 and 0.9 m, branch 4 at 0.2 m.
  struct Placed {
    int id, branch;
    double s;
  };
  const std::vector<Placed> placed = {{10, 0, 0.8}, {11, 1, 0.3}, {12, 1, 0.9}, {13, 4, 0.2}};
  Trajectories t;
  for (const Placed& p : placed) t.tracks.push_back(MarkerTrack{p.id, {}, {}});
  std::vector<Eigen::Vector3d> camera;
  for (const Placed& p : placed) {
    const Branch& b = tree.branches[p.branch];
    // On the surface: offset from the axis by the radius, along the frame's u.
    const Eigen::Vector3d world = b.PointAt(p.s) + b.frame.u * 0.9 * 0.01;
    camera.push_back(world_from_camera.inverse() * world);
  }
  for (int f = 0; f < 10; ++f) t.AddFrame(f, f / 30.0, camera, std::vector<bool>(4, true));
  const std::vector<MarkerPlacement> placements = PlaceMarkersOnTree(tree, t, world_from_camera);
  ASSERT_EQ(placements.size(), 4u);
  for (size_t i = 0; i < placed.size(); ++i) {
    EXPECT_EQ(placements[i].branch, placed[i].branch) << placed[i].id;
    EXPECT_NEAR(placements[i].arc_length, placed[i].s, 0.01) << placed[i].id;
    EXPECT_LT(placements[i].distance_m, 1e-6);
  }
  const std::vector<MarkerLink> links = LinkMarkersByTree(tree, placements);
  ASSERT_EQ(links.size(), 4u);
  auto parent_of = [&](int id) {
    for (const MarkerLink& l : links) {
      if (l.id == id) return l.parent;
    }
    return -99;
  };
  EXPECT_EQ(parent_of(10), -1);
  EXPECT_EQ(parent_of(11), 10);
  EXPECT_EQ(parent_of(12), 11);
  EXPECT_EQ(parent_of(13), 11);  // branch 4 starts at 0.6 m on branch 1: below it is marker 11
}

TEST(MarkerAssignment, WithoutATrunkMarkerTheLowestBecomesTheRoot) {
  const Tree tree = test::IdentificationTree();
  std::vector<MarkerPlacement> p(3);
  const int ids[3] = {1, 2, 3}, branches[3] = {2, 3, -1};  // marker 3 is never valid
  const double arcs[3] = {0.5, 0.2, 0.0};
  for (int i = 0; i < 3; ++i) {
    p[i].marker = ids[i];
    p[i].branch = branches[i];
    p[i].arc_length = arcs[i];
  }
  const std::vector<MarkerLink> links = LinkMarkersByTree(tree, p);
  ASSERT_EQ(links.size(), 2u);
  EXPECT_EQ(links[0].id, 1);
  EXPECT_EQ(links[0].parent, -1);
  EXPECT_EQ(links[1].parent, 1);
}

}  // namespace
}  // namespace simtree::identification
