#pragma once
// A triangle mesh with what simtree's meshes carry per vertex: normal, texture coordinate and the
// id of the branch it belongs to.

#include <vector>

#include <Eigen/Core>

namespace simtree {

struct TriangleMesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3f> normals;
  std::vector<Eigen::Vector2f> uvs;        // u around the branch in [0, 1], v along it in metres
  std::vector<int> branch_ids;             // per vertex
  std::vector<Eigen::Vector3i> triangles;  // counter-clockwise seen from outside

  size_t vertex_count() const { return vertices.size(); }
  size_t triangle_count() const { return triangles.size(); }
  void Clear();
  void Reserve(size_t vertex_count, size_t triangle_count);
};

}  // namespace simtree
