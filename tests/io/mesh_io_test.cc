#include "simtree/io/mesh_io.h"

#include <gtest/gtest.h>
#include <open3d/geometry/BoundingVolume.h>
#include <open3d/geometry/TriangleMesh.h>
#include <open3d/io/TriangleMeshIO.h>

#include "simtree/core/error.h"
#include "simtree/core/legacy_format.h"
#include "simtree/core/tube_mesh.h"
#include "test_util.h"

namespace simtree {
namespace {

TEST(MeshIo, Open3DReadsThePlyBackWithTheTreesBounds) {
  const Tree tree = ReadLegacyTree(test::SharedData("authors-demo/tree_model/tree01.txt"));
  const TriangleMesh mesh = BuildTubeMesh(tree);
  const auto dir = test::TempDir();
  MeshWriteOptions options;
  options.colour_by_level_of = &tree;
  WriteMesh(mesh, dir / "tree.ply", options);

  open3d::geometry::TriangleMesh read;
  ASSERT_TRUE(open3d::io::ReadTriangleMesh((dir / "tree.ply").string(), read));
  EXPECT_EQ(read.vertices_.size(), mesh.vertex_count());
  EXPECT_EQ(read.triangles_.size(), mesh.triangle_count());
  EXPECT_TRUE(read.HasVertexNormals());
  EXPECT_TRUE(read.HasVertexColors());
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  const auto box = read.GetAxisAlignedBoundingBox();
  // Tree::Bounds grows every node by its radius in all directions; the tubes lie inside that and,
  // across the branches, within a few centimetres of it, except at the trunk's flat base cap.
  lo.z() = tree.trunk().base().position.z();
  for (int k = 0; k < 3; ++k) {
    EXPECT_GE(box.min_bound_[k], lo[k] - 1e-5);
    EXPECT_LE(box.max_bound_[k], hi[k] + 1e-5);
    EXPECT_NEAR(box.min_bound_[k], lo[k], 0.02);
    EXPECT_NEAR(box.max_bound_[k], hi[k], 0.02);
  }
  EXPECT_TRUE(read.IsEdgeManifold());
}

TEST(MeshIo, PlyCarriesBranchIds) {
  const Tree tree = ReadLegacyTree(test::SharedData("authors-demo/tree_model/tree01.txt"));
  const auto dir = test::TempDir();
  WriteMesh(BuildTubeMesh(tree), dir / "tree.ply");
  const std::string bytes = test::ReadText(dir / "tree.ply");
  const size_t header_end = bytes.find("end_header\n");
  ASSERT_NE(header_end, std::string::npos);
  EXPECT_NE(bytes.substr(0, header_end).find("property int branch_id"), std::string::npos);
  // Last vertex (6 floats + id) belongs to the last branch.
  const TriangleMesh mesh = BuildTubeMesh(tree);
  const size_t vertex_bytes = 6 * 4 + 4;
  int32_t id = -1;
  std::memcpy(&id, bytes.data() + header_end + 11 + vertex_bytes * mesh.vertex_count() - 4, 4);
  EXPECT_EQ(id, tree.size() - 1);
}

TEST(MeshIo, ObjHasOneObjectPerBranch) {
  const Tree tree = ReadLegacyTree(test::SharedData("authors-demo/tree_model/tree02.txt"));
  const auto dir = test::TempDir();
  const TriangleMesh mesh = BuildTubeMesh(tree);
  WriteMesh(mesh, dir / "tree.obj");
  const std::string text = test::ReadText(dir / "tree.obj");
  size_t objects = 0, faces = 0;
  for (size_t at = 0; (at = text.find("\no branch_", at)) != std::string::npos; ++at) ++objects;
  for (size_t at = 0; (at = text.find("\nf ", at)) != std::string::npos; ++at) ++faces;
  EXPECT_EQ(objects, static_cast<size_t>(tree.size()));
  EXPECT_EQ(faces, mesh.triangle_count());
  open3d::geometry::TriangleMesh read;
  ASSERT_TRUE(open3d::io::ReadTriangleMesh((dir / "tree.obj").string(), read));
  EXPECT_EQ(read.triangles_.size(), mesh.triangle_count());
}

TEST(MeshIo, UnknownExtensionIsAnErrorAndWritesNothing) {
  const auto dir = test::TempDir();
  EXPECT_THROW(WriteMesh(TriangleMesh{}, dir / "tree.stl"), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

}  // namespace
}  // namespace simtree
