#include "simtree/core/mesh.h"

namespace simtree {

void TriangleMesh::Clear() {
  vertices.clear();
  normals.clear();
  uvs.clear();
  branch_ids.clear();
  triangles.clear();
}

void TriangleMesh::Reserve(size_t vertex_count, size_t triangle_count) {
  vertices.reserve(vertex_count);
  normals.reserve(vertex_count);
  uvs.reserve(vertex_count);
  branch_ids.reserve(vertex_count);
  triangles.reserve(triangle_count);
}

}  // namespace simtree
