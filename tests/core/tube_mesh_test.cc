#include "simtree/core/tube_mesh.h"

#include <map>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "core/tree_fixtures.h"
#include "simtree/core/units.h"

namespace simtree {
namespace {

// Counts directed edges by vertex position (seams and caps duplicate vertices on purpose).
using Key = std::array<float, 6>;
Key EdgeKey(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  return {a.x(), a.y(), a.z(), b.x(), b.y(), b.z()};
}

TEST(TubeMesh, EveryBranchIsAClosedOutwardTube) {
  const Tree tree = test::SmallTree();
  const TriangleMesh mesh = BuildTubeMesh(tree);
  ASSERT_EQ(mesh.vertices.size(), mesh.branch_ids.size());
  for (const Branch& b : tree.branches) {
    std::map<Key, int> directed;
    double volume = 0.0;  // divergence theorem: positive when triangles face outwards
    for (const Eigen::Vector3i& t : mesh.triangles) {
      if (mesh.branch_ids[t[0]] != b.id) continue;
      for (int k = 0; k < 3; ++k) {
        ++directed[EdgeKey(mesh.vertices[t[k]], mesh.vertices[t[(k + 1) % 3]])];
      }
      volume += mesh.vertices[t[0]].cast<double>().dot(
                    mesh.vertices[t[1]].cast<double>().cross(mesh.vertices[t[2]].cast<double>())) /
                6.0;
    }
    ASSERT_FALSE(directed.empty());
    for (const auto& [key, count] : directed) {
      EXPECT_EQ(count, 1) << "branch " << b.id << ": an edge used twice in one direction";
      const Key reverse = {key[3], key[4], key[5], key[0], key[1], key[2]};
      EXPECT_EQ(directed.count(reverse), 1u) << "branch " << b.id << ": an open edge";
    }
    // A 12-gon prism holds 12 sin(30 deg) / (2 pi) = 0.955 of the round frustums' volume.
    const double polygon = 12 * std::sin(kTwoPi / 12) / kTwoPi;
    EXPECT_NEAR(volume, polygon * b.Volume(), 1e-3 * b.Volume()) << "branch " << b.id;
  }
}

TEST(TubeMesh, RingsLieAtTheRadiusAroundTheAxis) {
  Tree tree = test::SmallTree();
  tree.branches.resize(1);
  TubeMeshOptions options;
  options.caps = false;
  options.sides = 8;
  const TriangleMesh mesh = BuildTubeMesh(tree, options);
  ASSERT_EQ(mesh.vertices.size(), 5u * 9u);
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const int ring = static_cast<int>(i / 9);
    const Eigen::Vector3d v = mesh.vertices[i].cast<double>();
    const Eigen::Vector3d c = tree.trunk().nodes[ring].position;
    EXPECT_NEAR((v - c).norm(), tree.trunk().nodes[ring].radius, 1e-6);
    EXPECT_NEAR((v - c).dot(Eigen::Vector3d::UnitZ()), 0.0, 1e-6);
    EXPECT_NEAR(mesh.normals[i].norm(), 1.0, 1e-6);
  }
}

TEST(TubeMesh, DuplicateNodesDoNotBreakTheTube) {
  Tree tree = test::SmallTree();
  tree.branches.resize(1);
  auto& nodes = tree.branches[0].nodes;
  nodes.insert(nodes.begin() + 2, nodes[2]);  // zero-length segment
  const TriangleMesh mesh = BuildTubeMesh(tree);
  for (const auto& v : mesh.vertices) EXPECT_TRUE(v.allFinite());
  for (const auto& n : mesh.normals) EXPECT_TRUE(n.allFinite());
}

}  // namespace
}  // namespace simtree
