#pragma once
// Mesh files: PLY (binary, per-vertex normal, colour by branch level and an integer `branch_id`
// property) and Wavefront OBJ (one object `branch_<id>` per branch, normals and texture
// coordinates). Open3D, CloudCompare, MeshLab and Blender open both.

#include <filesystem>

#include "simtree/core/mesh.h"
#include "simtree/core/tree.h"

namespace simtree {

struct MeshWriteOptions {
  // Per-vertex colour by the branch level (helps in CloudCompare/MeshLab); needs the tree.
  const Tree* colour_by_level_of = nullptr;
};

// Writes by extension: .ply or .obj (InputError otherwise). Atomic.
// Throws InputError naming `path` for another extension (CheckMeshPath, before any work).
void CheckMeshPath(const std::filesystem::path& path);
void WriteMesh(const TriangleMesh& mesh, const std::filesystem::path& path,
               const MeshWriteOptions& options = {});
void WritePlyMesh(const TriangleMesh& mesh, const std::filesystem::path& path,
                  const MeshWriteOptions& options = {});
void WriteObjMesh(const TriangleMesh& mesh, const std::filesystem::path& path);

// A distinct colour per level (trunk brown, then lighter greens/blues), RGB in [0, 255].
Eigen::Vector3i LevelColour(int level);

}  // namespace simtree
