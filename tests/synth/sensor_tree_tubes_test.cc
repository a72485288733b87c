#include "simtree/synth/detail/sensor_tree_tubes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/tree_fixtures.h"

namespace simtree::synth {
namespace {

TEST(TreeTubes, SidesKeepTheFacetsWithinTheTolerance) {
  const TreeTubeOptions options;
  for (double r : {0.002, 0.005, 0.01, 0.03, 0.1}) {
    const int n = TubeSides(r, options);
    EXPECT_LE(r * (1.0 - std::cos(std::numbers::pi / n)), options.tolerance_m + 1e-12) << r;
    EXPECT_GE(n, options.min_sides);
  }
  EXPECT_EQ(TubeSides(10.0, options), options.max_sides);  // capped
  EXPECT_EQ(TubeSides(1e-5, options), options.min_sides);
}

TEST(TreeTubes, RingsLieOnTheTrueCirclesAtTheNodes) {
  const Tree tree = test::SmallTree();
  const TreeTubes tubes(tree);
  const TreePose pose(tree);
  std::vector<float> v(3 * static_cast<size_t>(tubes.vertex_count()));
  tubes.WriteVertices(tree, pose, v.data());
  int segments = 0;
  for (const Branch& b : tree.branches) {
    const int sides = tubes.sides(b.id);
    const int nodes = static_cast<int>(b.nodes.size());
    EXPECT_EQ(tubes.branch_vertex_count(b.id), nodes * sides + 2);
    segments += nodes - 1;
    for (int i = 0; i < nodes; ++i) {
      for (int k = 0; k < sides; ++k) {
        const float* p = &v[3 * static_cast<size_t>(tubes.vertex_offset(b.id) + i * sides + k)];
        const Eigen::Vector3d q(p[0], p[1], p[2]);
        EXPECT_NEAR((q - b.nodes[i].position).norm(), b.nodes[i].radius, 1e-6);
      }
    }
  }
  EXPECT_EQ(tubes.segment_count(), segments);
  // Every triangle's vertices belong to its segment's branch, and its segment's nodes.
  for (int t = 0; t < tubes.triangle_count(); ++t) {
    const int b = tubes.segment_branch(tubes.triangle_segment(t));
    for (int c = 0; c < 3; ++c) {
      const int vertex = tubes.triangles()[t][c];
      ASSERT_GE(vertex, tubes.vertex_offset(b));
      ASSERT_LT(vertex, tubes.vertex_offset(b) + tubes.branch_vertex_count(b));
    }
  }
}

}  // namespace
}  // namespace simtree::synth
