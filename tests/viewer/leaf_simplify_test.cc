// Leaf simplification: a flat blade collapses to its corners, a crease deeper than the tolerance
// stays, the authors' leaves keep their outline, area and texture coordinates with far fewer
// triangles, the petiole is thinned, and a bad tolerance is an InputError.

#include "simtree/viewer/detail/leaf_simplify.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "simtree/core/error.h"
#include "viewer_fixtures.h"

namespace simtree::viewer {
namespace {

// A 1 x 1 blade in z = height(x, y), n x n quads, u = x, v = y; a straight petiole to (0, 0.5).
LeafModel GridBlade(int n, float (*height)(float, float)) {
  LeafModel m;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const float x = static_cast<float>(i) / n, y = static_cast<float>(j) / n;
      m.vertices.emplace_back(x, y, height(x, y));
      m.uvs.emplace_back(x, y);
    }
  }
  auto at = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  for (int k = 0; k <= 4; ++k) {
    m.petiole_points.emplace_back(-0.1f * static_cast<float>(4 - k), 0.5f, 0.0f);
    m.petiole_radii.push_back(0.01f);
  }
  return m;
}

float Flat(float, float) { return 0.0f; }
// A crease along y = 0.5, 0.1 above the blade's edges.
float Creased(float, float y) { return 0.1f - 0.2f * std::abs(y - 0.5f); }

double Area(const LeafModel& m) {
  double area = 0.0;
  for (const Eigen::Vector3i& t : m.triangles) {
    area += 0.5 *
            (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).norm();
  }
  return area;
}

// Every vertex of `out` is a vertex of `in` with the same texture coordinate.
void ExpectKeptVertices(const LeafModel& in, const LeafModel& out) {
  ASSERT_EQ(out.uvs.size(), out.vertices.size());
  for (size_t v = 0; v < out.vertices.size(); ++v) {
    const auto it = std::find(in.vertices.begin(), in.vertices.end(), out.vertices[v]);
    ASSERT_NE(it, in.vertices.end()) << "vertex " << v << " is new";
    EXPECT_EQ(in.uvs[static_cast<size_t>(it - in.vertices.begin())], out.uvs[v]);
  }
  for (const Eigen::Vector3i& t : out.triangles) {
    EXPECT_TRUE(t.minCoeff() >= 0 && t.maxCoeff() < static_cast<int>(out.vertices.size()));
  }
}

// Distance from `p` to the triangle (a, b, c), by its barycentric clamp on the plane or the
// nearest edge.
double PointTriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                             const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  if (n.norm() > 1e-15) {
    const Eigen::Vector3d q = p - n.dot(p - a) / n.squaredNorm() * n;
    const double wa = (b - q).cross(c - q).dot(n), wb = (c - q).cross(a - q).dot(n),
                 wc = (a - q).cross(b - q).dot(n);
    if (wa >= 0 && wb >= 0 && wc >= 0) return (p - q).norm();
  }
  auto segment = [&](const Eigen::Vector3d& s, const Eigen::Vector3d& e) {
    const Eigen::Vector3d d = e - s;
    const double t =
        d.squaredNorm() > 0 ? std::clamp((p - s).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    return (p - (s + t * d)).norm();
  };
  return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

// The largest distance from a vertex of `in` to the surface of `out`.
double LargestDeviation(const LeafModel& in, const LeafModel& out) {
  double worst = 0.0;
  for (const Eigen::Vector3f& v : in.vertices) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3i& t : out.triangles) {
      nearest = std::min(nearest,
                         PointTriangleDistance(v.cast<double>(), out.vertices[t[0]].cast<double>(),
                                               out.vertices[t[1]].cast<double>(),
                                               out.vertices[t[2]].cast<double>()));
    }
    worst = std::max(worst, nearest);
  }
  return worst;
}

TEST(LeafSimplify, AFlatSquareBladeCollapsesToTwoTriangles) {
  const LeafModel in = GridBlade(6, Flat);
  const LeafSimplifyResult r = SimplifyLeafModel(in, {.tolerance = 1e-4});
  EXPECT_EQ(r.blade_triangles_before, 72);
  EXPECT_EQ(r.model.triangles.size(), 2u);
  EXPECT_EQ(r.model.vertices.size(), 4u);
  EXPECT_NEAR(Area(r.model), 1.0, 1e-6);
  EXPECT_LE(r.max_error, 1e-6);
  ExpectKeptVertices(in, r.model);
  // Still facing +z.
  for (const Eigen::Vector3i& t : r.model.triangles) {
    const Eigen::Vector3f n = (r.model.vertices[t[1]] - r.model.vertices[t[0]])
                                  .cross(r.model.vertices[t[2]] - r.model.vertices[t[0]]);
    EXPECT_GT(n.z(), 0.0f);
  }
  // The straight petiole keeps its ends only.
  ASSERT_EQ(r.model.petiole_points.size(), 2u);
  EXPECT_EQ(r.model.petiole_points.front(), in.petiole_points.front());
  EXPECT_EQ(r.model.petiole_points.back(), in.petiole_points.back());
  EXPECT_EQ(r.model.petiole_radii.size(), 2u);
}

TEST(LeafSimplify, ACreaseDeeperThanTheToleranceStays) {
  const LeafModel in = GridBlade(6, Creased);
  const float length = in.Length();
  // 0.1 deep: kept at a tolerance of 0.05 (in units of the length), flattened at 0.2.
  const LeafSimplifyResult kept = SimplifyLeafModel(in, {.tolerance = 0.05 / length});
  float top = 0.0f;
  for (const Eigen::Vector3f& v : kept.model.vertices) top = std::max(top, v.z());
  EXPECT_FLOAT_EQ(top, 0.1f);
  EXPECT_LT(kept.model.triangles.size(), in.triangles.size());
  EXPECT_LE(LargestDeviation(in, kept.model), 0.05);
  ExpectKeptVertices(in, kept.model);
  const LeafSimplifyResult flat = SimplifyLeafModel(in, {.tolerance = 0.2 / length});
  EXPECT_EQ(flat.model.triangles.size(), 2u);
  EXPECT_LE(LargestDeviation(in, flat.model), 0.1 + 1e-6);
}

TEST(LeafSimplify, AuthorsLeavesKeepTheirShapeWithFarFewerTriangles) {
  for (const char* name : {"apple_leaf", "maple_leaf"}) {
    SCOPED_TRACE(name);
    const LeafModel in =
        ReadLeafModel(test::SharedData("authors-demo/leaf_model") / name / "leaf.txt");
    const LeafSimplifyOptions options;  // the renderer's default
    const LeafSimplifyResult r = SimplifyLeafModel(in, options);
    const double tolerance = options.tolerance * in.Length();
    EXPECT_LE(r.model.triangles.size() * 3, in.triangles.size());
    EXPECT_LE(r.max_error, tolerance);
    EXPECT_LE(LargestDeviation(in, r.model), 2.0 * tolerance);
    // The outline through the apple's tooth tips fills the notches between them: a few %.
    EXPECT_NEAR(Area(r.model), Area(in), 0.05 * Area(in));
    ExpectKeptVertices(in, r.model);
    EXPECT_FLOAT_EQ(r.model.Length(), in.Length());
    EXPECT_EQ(r.model.petiole_points.front(), in.petiole_points.front());
    EXPECT_EQ(r.model.petiole_points.back(), in.petiole_points.back());
  }
}

TEST(LeafSimplify, ZeroToleranceKeepsTheModel) {
  const LeafModel in = ReadLeafModel(test::AppleLeaf() / "leaf.txt");
  const LeafSimplifyResult r = SimplifyLeafModel(in, {.tolerance = 0.0});
  EXPECT_EQ(r.model.triangles, in.triangles);
  EXPECT_EQ(r.model.vertices, in.vertices);
  EXPECT_EQ(r.model.petiole_points, in.petiole_points);
  EXPECT_EQ(r.max_error, 0.0);
}

TEST(LeafSimplify, ABladeAboveTheSizeLimitIsKeptButItsPetioleThinned) {
  const LeafModel in = GridBlade(6, Flat);
  const LeafSimplifyResult r = SimplifyLeafModel(in, {.tolerance = 0.01, .max_blade_vertices = 10});
  EXPECT_EQ(r.model.triangles.size(), in.triangles.size());
  EXPECT_EQ(r.model.petiole_points.size(), 2u);
}

TEST(LeafSimplify, ABadToleranceIsAnInputError) {
  const LeafModel in = GridBlade(2, Flat);
  for (double bad : {-0.01, std::nan(""), std::numeric_limits<double>::infinity()}) {
    EXPECT_THROW(SimplifyLeafModel(in, {.tolerance = bad}), InputError) << bad;
    EXPECT_EQ(test::InputErrorField([&] { LeafSimplifyOptions{.tolerance = bad}.Validate(); }),
              "tolerance");
  }
  EXPECT_EQ(test::InputErrorField([] { LeafSimplifyOptions{.max_blade_vertices = -1}.Validate(); }),
            "max_blade_vertices");
}

}  // namespace
}  // namespace simtree::viewer
