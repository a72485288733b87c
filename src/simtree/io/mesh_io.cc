#include "simtree/io/mesh_io.h"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"

namespace simtree {
namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

template <typename T>
void Put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value,
              sizeof(T));  // x86-64 and aarch64 are little endian, as the header says
  out.append(bytes, sizeof(T));
}

}  // namespace

Eigen::Vector3i LevelColour(int level) {
  static const Eigen::Vector3i kColours[] = {{110, 75, 45},  {60, 140, 60},  {50, 110, 190},
                                             {0, 200, 130},  {200, 60, 200}, {240, 150, 30},
                                             {200, 200, 60}, {120, 120, 120}};
  constexpr int kCount = static_cast<int>(std::size(kColours));
  return kColours[std::clamp(level, 0, kCount - 1)];
}

void CheckMeshPath(const std::filesystem::path& path) {
  const std::string ext = Lower(path.extension().string());
  if (ext != ".ply" && ext != ".obj") {
    throw InputError(path.string(), "",
                     fmt::format("expected a mesh file ending in .ply or .obj, got \"{}\"", ext));
  }
}

void WriteMesh(const TriangleMesh& mesh, const std::filesystem::path& path,
               const MeshWriteOptions& options) {
  CheckMeshPath(path);
  if (Lower(path.extension().string()) == ".ply") {
    WritePlyMesh(mesh, path, options);
  } else {
    WriteObjMesh(mesh, path);
  }
}

void WritePlyMesh(const TriangleMesh& mesh, const std::filesystem::path& path,
                  const MeshWriteOptions& options) {
  const bool colour = options.colour_by_level_of != nullptr;
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment simtree generalized cylinders\n";
  out += fmt::format("element vertex {}\n", mesh.vertex_count());
  out += "property float x\nproperty float y\nproperty float z\n";
  out += "property float nx\nproperty float ny\nproperty float nz\n";
  if (colour) out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  out += "property int branch_id\n";
  out += fmt::format("element face {}\n", mesh.triangle_count());
  out += "property list uchar int vertex_indices\nend_header\n";
  out.reserve(out.size() + mesh.vertex_count() * 31 + mesh.triangle_count() * 13);
  for (size_t i = 0; i < mesh.vertex_count(); ++i) {
    for (int k = 0; k < 3; ++k) Put(out, mesh.vertices[i][k]);
    for (int k = 0; k < 3; ++k) Put(out, mesh.normals[i][k]);
    if (colour) {
      const int id = mesh.branch_ids[i];
      const auto& branches = options.colour_by_level_of->branches;
      const int level = id >= 0 && id < static_cast<int>(branches.size()) ? branches[id].level : 0;
      const Eigen::Vector3i c = LevelColour(level);
      for (int k = 0; k < 3; ++k) Put(out, static_cast<uint8_t>(c[k]));
    }
    Put(out, static_cast<int32_t>(mesh.branch_ids[i]));
  }
  for (const Eigen::Vector3i& t : mesh.triangles) {
    Put(out, static_cast<uint8_t>(3));
    for (int k = 0; k < 3; ++k) Put(out, static_cast<int32_t>(t[k]));
  }
  WriteFileAtomically(path, out);
}

void WriteObjMesh(const TriangleMesh& mesh, const std::filesystem::path& path) {
  std::string out = "# simtree generalized cylinders: one object per branch\n";
  for (size_t i = 0; i < mesh.vertex_count(); ++i) {
    const auto& v = mesh.vertices[i];
    out += fmt::format("v {} {} {}\n", v.x(), v.y(), v.z());
  }
  for (size_t i = 0; i < mesh.vertex_count(); ++i) {
    const auto& n = mesh.normals[i];
    out += fmt::format("vn {} {} {}\n", n.x(), n.y(), n.z());
  }
  for (size_t i = 0; i < mesh.vertex_count(); ++i) {
    const auto& t = mesh.uvs[i];
    out += fmt::format("vt {} {}\n", t.x(), t.y());
  }
  int current = -1;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const int id = mesh.branch_ids[t[0]];
    if (id != current) {
      out += fmt::format("o branch_{}\n", id);
      current = id;
    }
    out += fmt::format("f {0}/{0}/{0} {1}/{1}/{1} {2}/{2}/{2}\n", t[0] + 1, t[1] + 1, t[2] + 1);
  }
  WriteFileAtomically(path, out);
}

}  // namespace simtree
