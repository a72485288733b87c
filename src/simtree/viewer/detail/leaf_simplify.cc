#include "simtree/viewer/detail/leaf_simplify.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"

namespace simtree::viewer {
namespace {

using Plane = Eigen::Vector4d;  // unit normal and offset: n . p + d = 0
using Edge = std::pair<int, int>;

Edge Undirected(int a, int b) { return a < b ? Edge(a, b) : Edge(b, a); }

double Distance(const Plane& plane, const Eigen::Vector3d& p) {
  return std::abs(plane.head<3>().dot(p) + plane.w());
}

double SegmentDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                       const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double s =
      ab.squaredNorm() > 0.0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

// Distance from `p` to the triangle (a, b, c): to its plane when `p` projects inside, else to the
// nearest edge.
double TriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                        const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  if (n.squaredNorm() > 0.0) {
    const Eigen::Vector3d q = p - n.dot(p - a) / n.squaredNorm() * n;
    if ((b - q).cross(c - q).dot(n) >= 0.0 && (c - q).cross(a - q).dot(n) >= 0.0 &&
        (a - q).cross(b - q).dot(n) >= 0.0) {
      return (p - q).norm();
    }
  }
  return std::min({SegmentDistance(p, a, b), SegmentDistance(p, b, c), SegmentDistance(p, c, a)});
}

// The blade as a mutable triangle soup: dead triangles and vertices are kept, flagged.
class BladeSimplifier {
 public:
  explicit BladeSimplifier(const LeafModel& model) : triangles_(model.triangles) {
    for (const Eigen::Vector3f& v : model.vertices) positions_.push_back(v.cast<double>());
    planes_.resize(positions_.size());
    for (const Eigen::Vector3d& p : positions_) represented_.push_back({p});
    triangle_alive_.assign(triangles_.size(), true);
    Rebuild();
    // Every face's plane, on each of its corners.
    for (const Eigen::Vector3i& t : triangles_) {
      const Eigen::Vector3d n = Normal(t, -1, {});
      if (n.norm() < 1e-12) continue;
      for (int k = 0; k < 3; ++k)
        planes_[t[k]].push_back(PlaneThrough(n.normalized(), positions_[t[k]]));
    }
  }

  // Collapses the cheapest edge while it costs at most `tolerance`; returns the largest cost
  // accepted.
  double Run(double tolerance) {
    double worst = 0.0;
    for (;;) {
      double best_cost = std::numeric_limits<double>::infinity();
      int best_from = -1, best_to = -1;
      for (const auto& [edge, faces] : edge_faces_) {
        for (const auto& [from, to] : {edge, Edge(edge.second, edge.first)}) {
          if (!CanCollapse(from, to, faces)) continue;
          double cost = 0.0;
          for (const Plane& plane : planes_[from]) {
            cost = std::max(cost, Distance(plane, positions_[to]));
          }
          if (cost >= best_cost || cost > tolerance) continue;
          cost = std::max(cost, PointCost(from, to));
          if (cost < best_cost) {
            best_cost = cost;
            best_from = from;
            best_to = to;
          }
        }
      }
      if (best_from < 0 || best_cost > tolerance) return worst;
      Collapse(best_from, best_to);
      worst = std::max(worst, best_cost);
    }
  }

  // The surviving triangles, on the surviving vertices renumbered in their old order.
  void Write(const LeafModel& in, LeafModel& out) const {
    std::vector<int> renumber(positions_.size(), -1);
    for (size_t t = 0; t < triangles_.size(); ++t) {
      if (!triangle_alive_[t]) continue;
      for (int k = 0; k < 3; ++k) renumber[triangles_[t][k]] = 0;
    }
    out.vertices.clear();
    out.uvs.clear();
    for (size_t v = 0; v < renumber.size(); ++v) {
      if (renumber[v] < 0) continue;
      renumber[v] = static_cast<int>(out.vertices.size());
      out.vertices.push_back(in.vertices[v]);
      out.uvs.push_back(in.uvs[v]);
    }
    out.triangles.clear();
    for (size_t t = 0; t < triangles_.size(); ++t) {
      if (!triangle_alive_[t]) continue;
      const Eigen::Vector3i& old = triangles_[t];
      out.triangles.emplace_back(renumber[old[0]], renumber[old[1]], renumber[old[2]]);
    }
  }

 private:
  static Plane PlaneThrough(const Eigen::Vector3d& unit_normal, const Eigen::Vector3d& point) {
    return Plane(unit_normal.x(), unit_normal.y(), unit_normal.z(), -unit_normal.dot(point));
  }

  // The triangle's (unnormalised) normal, with vertex `moved` (if any) at `at`.
  Eigen::Vector3d Normal(const Eigen::Vector3i& t, int moved, const Eigen::Vector3d& at) const {
    auto p = [&](int k) -> const Eigen::Vector3d& { return t[k] == moved ? at : positions_[t[k]]; };
    return (p(1) - p(0)).cross(p(2) - p(0));
  }

  // Adjacency of the surviving triangles.
  void Rebuild() {
    edge_faces_.clear();
    vertex_triangles_.assign(positions_.size(), {});
    neighbours_.assign(positions_.size(), {});
    for (size_t t = 0; t < triangles_.size(); ++t) {
      if (!triangle_alive_[t]) continue;
      for (int k = 0; k < 3; ++k) {
        const int a = triangles_[t][k];
        const int b = triangles_[t][(k + 1) % 3];
        ++edge_faces_[Undirected(a, b)];
        vertex_triangles_[a].push_back(static_cast<int>(t));
        neighbours_[a].insert(b);
        neighbours_[b].insert(a);
      }
    }
    on_boundary_.assign(positions_.size(), false);
    for (const auto& [edge, faces] : edge_faces_) {
      if (faces == 1) on_boundary_[edge.first] = on_boundary_[edge.second] = true;
    }
  }

  // Whether merging `from` into `to` (an edge of `faces` triangles) keeps the blade a manifold
  // with the same outline topology and no face turned over.
  bool CanCollapse(int from, int to, int faces) const {
    if (faces > 2) return false;
    // A boundary vertex may only slide along the boundary, or the blade would pinch.
    if (on_boundary_[from] && faces != 1) return false;
    if (static_cast<int>(alive_triangles()) <= faces) return false;
    // Link condition: the two ends share exactly the apexes of the triangles on their edge.
    int shared = 0;
    for (int n : neighbours_[from]) shared += neighbours_[to].count(n) > 0 ? 1 : 0;
    if (shared != faces) return false;
    for (int t : vertex_triangles_[from]) {
      const Eigen::Vector3i& tri = triangles_[t];
      if (tri[0] == to || tri[1] == to || tri[2] == to) continue;  // removed by the collapse
      const Eigen::Vector3d before = Normal(tri, -1, {});
      const Eigen::Vector3d after = Normal(tri, from, positions_[to]);
      if (after.norm() < 1e-6 * before.norm() || after.dot(before) <= 0.0) return false;
    }
    return true;
  }

  // The largest distance from the original vertices both ends stand for to the triangles `to`
  // would have: what holds the outline (the face planes run on without end, so a lobe could
  // vanish along them at no cost).
  double PointCost(int from, int to) const {
    double worst = 0.0;
    for (int end : {from, to}) {
      for (const Eigen::Vector3d& p : represented_[end]) {
        double nearest = std::numeric_limits<double>::infinity();
        for (int t : {from, to}) {
          for (int f : vertex_triangles_[t]) {
            const Eigen::Vector3i& tri = triangles_[f];
            const bool has_from = tri[0] == from || tri[1] == from || tri[2] == from;
            const bool has_to = tri[0] == to || tri[1] == to || tri[2] == to;
            if (has_from && has_to) continue;  // removed by the collapse
            auto at = [&](int k) -> const Eigen::Vector3d& {
              return tri[k] == from ? positions_[to] : positions_[tri[k]];
            };
            nearest = std::min(nearest, TriangleDistance(p, at(0), at(1), at(2)));
          }
        }
        worst = std::max(worst, nearest);
      }
    }
    return worst;
  }

  size_t alive_triangles() const {
    return static_cast<size_t>(std::count(triangle_alive_.begin(), triangle_alive_.end(), true));
  }

  void Collapse(int from, int to) {
    for (int t : vertex_triangles_[from]) {
      Eigen::Vector3i& tri = triangles_[t];
      if (tri[0] == to || tri[1] == to || tri[2] == to) {
        triangle_alive_[t] = false;
      } else {
        for (int k = 0; k < 3; ++k) {
          if (tri[k] == from) tri[k] = to;
        }
      }
    }
    planes_[to].insert(planes_[to].end(), planes_[from].begin(), planes_[from].end());
    planes_[from].clear();
    represented_[to].insert(represented_[to].end(), represented_[from].begin(),
                            represented_[from].end());
    represented_[from].clear();
    Rebuild();
  }

  std::vector<Eigen::Vector3d> positions_;
  std::vector<Eigen::Vector3i> triangles_;
  std::vector<bool> triangle_alive_;
  std::vector<std::vector<Plane>> planes_;                 // the planes each vertex answers for
  std::vector<std::vector<Eigen::Vector3d>> represented_;  // the original vertices it stands for
  std::map<Edge, int> edge_faces_;
  std::vector<std::vector<int>> vertex_triangles_;
  std::vector<std::set<int>> neighbours_;
  std::vector<bool> on_boundary_;
};

// Douglas-Peucker: the indices of the points kept (the ends always).
void ThinPolyline(const std::vector<Eigen::Vector3f>& points, size_t first, size_t last,
                  double tolerance, std::vector<bool>& keep, double& worst) {
  if (last <= first + 1) return;
  const Eigen::Vector3d a = points[first].cast<double>();
  const Eigen::Vector3d b = points[last].cast<double>();
  double farthest = -1.0;
  size_t at = first;
  for (size_t i = first + 1; i < last; ++i) {
    const double d = SegmentDistance(points[i].cast<double>(), a, b);
    if (d > farthest) {
      farthest = d;
      at = i;
    }
  }
  if (farthest <= tolerance) {
    worst = std::max(worst, farthest);
    return;
  }
  keep[at] = true;
  ThinPolyline(points, first, at, tolerance, keep, worst);
  ThinPolyline(points, at, last, tolerance, keep, worst);
}

}  // namespace

void LeafSimplifyOptions::Validate() const {
  CheckOption(tolerance >= 0.0 && std::isfinite(tolerance), "leaf simplification", "tolerance",
              fmt::format("expected a fraction of the leaf's length >= 0, got {}", tolerance));
  CheckOption(max_blade_vertices >= 0, "leaf simplification", "max_blade_vertices",
              fmt::format("expected >= 0, got {}", max_blade_vertices));
}

LeafSimplifyResult SimplifyLeafModel(const LeafModel& model, const LeafSimplifyOptions& options) {
  options.Validate();
  LeafSimplifyResult result;
  result.model = model;
  result.blade_triangles_before = static_cast<int>(model.triangles.size());
  result.petiole_points_before = static_cast<int>(model.petiole_points.size());
  const double tolerance = options.tolerance * model.Length();
  if (tolerance <= 0.0) return result;

  if (static_cast<int>(model.vertices.size()) <= options.max_blade_vertices) {
    BladeSimplifier blade(model);
    result.max_error = blade.Run(tolerance);
    blade.Write(model, result.model);
  }

  const std::vector<Eigen::Vector3f>& points = model.petiole_points;
  if (points.size() > 2) {
    std::vector<bool> keep(points.size(), false);
    keep.front() = keep.back() = true;
    ThinPolyline(points, 0, points.size() - 1, tolerance, keep, result.max_error);
    result.model.petiole_points.clear();
    result.model.petiole_radii.clear();
    for (size_t i = 0; i < points.size(); ++i) {
      if (!keep[i]) continue;
      result.model.petiole_points.push_back(points[i]);
      result.model.petiole_radii.push_back(model.petiole_radii[i]);
    }
  }
  return result;
}

}  // namespace simtree::viewer
