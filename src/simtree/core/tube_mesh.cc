#include "simtree/core/tube_mesh.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "simtree/core/error.h"
#include "simtree/core/units.h"

namespace simtree {
namespace {

// Unit tangent at node i: the bisector of the adjacent segments, skipping zero-length ones.
Eigen::Vector3d Tangent(std::span<const Eigen::Vector3d> c, size_t i, const Eigen::Vector3d& prev) {
  Eigen::Vector3d in = Eigen::Vector3d::Zero(), out = Eigen::Vector3d::Zero();
  if (i > 0) in = c[i] - c[i - 1];
  if (i + 1 < c.size()) out = c[i + 1] - c[i];
  if (in.norm() > 0) in.normalize();
  if (out.norm() > 0) out.normalize();
  Eigen::Vector3d t = in + out;
  return t.norm() > 1e-9 ? Eigen::Vector3d(t.normalized()) : prev;
}

}  // namespace

void AppendTube(std::span<const Eigen::Vector3d> centers, std::span<const double> radii,
                const Eigen::Vector3d& reference_u, int branch_id, const TubeMeshOptions& options,
                TriangleMesh& mesh) {
  const size_t n = centers.size();
  const int sides = std::max(3, options.sides);
  if (n < 2 || radii.size() != n) {
    throw Error("AppendTube: expected >= 2 centers and as many radii");
  }
  const auto first = static_cast<int>(mesh.vertices.size());
  // Grow geometrically: reserving exactly what each tube needs would reallocate the whole mesh on
  // every branch, quadratic in the tree's size (a 1,000-branch tree took 13 s).
  const size_t vertices_needed = mesh.vertices.size() + n * (sides + 1) + 2 * (sides + 1);
  const size_t triangles_needed = mesh.triangles.size() + 2 * (n - 1) * sides + 2 * sides;
  if (mesh.vertices.capacity() < vertices_needed || mesh.triangles.capacity() < triangles_needed) {
    mesh.Reserve(std::max(vertices_needed, 2 * mesh.vertices.capacity()),
                 std::max(triangles_needed, 2 * mesh.triangles.capacity()));
  }

  // Parallel-transported frame along the polyline.
  Eigen::Vector3d tangent = Tangent(centers, 0, Eigen::Vector3d::UnitZ());
  Eigen::Vector3d normal = reference_u - reference_u.dot(tangent) * tangent;
  if (normal.norm() < 1e-9) normal = tangent.unitOrthogonal();
  normal.normalize();
  double arc = 0.0;
  for (size_t i = 0; i < n; ++i) {
    if (i > 0) {
      const Eigen::Vector3d next = Tangent(centers, i, tangent);
      normal = Eigen::Quaterniond::FromTwoVectors(tangent, next) * normal;
      normal = (normal - normal.dot(next) * next).normalized();
      tangent = next;
      arc += (centers[i] - centers[i - 1]).norm();
    }
    const Eigen::Vector3d binormal = tangent.cross(normal);
    const double r = std::max(radii[i], options.min_radius);
    // sides + 1 vertices so the texture seam has its own column.
    for (int k = 0; k <= sides; ++k) {
      const double theta = kTwoPi * (k % sides) / sides;  // the seam repeats k = 0 exactly
      const Eigen::Vector3d dir = std::cos(theta) * normal + std::sin(theta) * binormal;
      mesh.vertices.push_back((centers[i] + r * dir).cast<float>());
      mesh.normals.push_back(dir.cast<float>());
      mesh.uvs.emplace_back(static_cast<float>(k) / sides, static_cast<float>(arc));
      mesh.branch_ids.push_back(branch_id);
    }
  }
  const int ring = sides + 1;
  for (size_t i = 0; i + 1 < n; ++i) {
    const int a = first + static_cast<int>(i) * ring;
    const int b = a + ring;
    for (int k = 0; k < sides; ++k) {
      mesh.triangles.emplace_back(a + k, a + k + 1, b + k + 1);
      mesh.triangles.emplace_back(a + k, b + k + 1, b + k);
    }
  }
  if (!options.caps) return;
  // Caps share the ring positions but have their own flat normals; the seam vertex of each ring
  // coincides with its first, so caps use `sides` vertices and a centre.
  for (int end = 0; end < 2; ++end) {
    const size_t i = end == 0 ? 0 : n - 1;
    const int ring_start = first + static_cast<int>(i) * ring;
    const Eigen::Vector3d axis = (end == 0 ? -1.0 : 1.0) * Tangent(centers, i, tangent);
    const int centre = static_cast<int>(mesh.vertices.size());
    mesh.vertices.push_back(centers[i].cast<float>());
    mesh.normals.push_back(axis.cast<float>());
    mesh.uvs.emplace_back(0.5f, mesh.uvs[ring_start].y());
    mesh.branch_ids.push_back(branch_id);
    for (int k = 0; k < sides; ++k) {
      mesh.vertices.push_back(mesh.vertices[ring_start + k]);
      mesh.normals.push_back(axis.cast<float>());
      mesh.uvs.push_back(mesh.uvs[ring_start + k]);
      mesh.branch_ids.push_back(branch_id);
    }
    for (int k = 0; k < sides; ++k) {
      const int v0 = centre + 1 + k;
      const int v1 = centre + 1 + (k + 1) % sides;
      // The ring runs counter-clockwise around +tangent: reverse it for the base cap.
      if (end == 0) {
        mesh.triangles.emplace_back(centre, v1, v0);
      } else {
        mesh.triangles.emplace_back(centre, v0, v1);
      }
    }
  }
}

TriangleMesh BuildTubeMesh(const Tree& tree, const TubeMeshOptions& options) {
  TriangleMesh mesh;
  std::vector<Eigen::Vector3d> centers;
  std::vector<double> radii;
  for (const Branch& b : tree.branches) {
    centers.clear();
    radii.clear();
    for (const Node& node : b.nodes) {
      centers.push_back(node.position);
      radii.push_back(node.radius);
    }
    AppendTube(centers, radii, b.frame.u, b.id, options, mesh);
  }
  return mesh;
}

}  // namespace simtree
