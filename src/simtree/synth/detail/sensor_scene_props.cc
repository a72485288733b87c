#include "simtree/synth/detail/sensor_scene_props.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <embree3/rtcore_geometry.h>

#include "simtree/synth/detail/textures.h"

namespace simtree::synth {

void CurveSet::AddPolyline(const std::vector<Eigen::Vector3d>& points,
                           const std::vector<double>& radii) {
  const auto first = static_cast<uint32_t>(vertices.size());
  const int n = static_cast<int>(points.size());
  double distance = 0.0;
  for (int i = 0; i < n; ++i) {
    if (i > 0) distance += (points[i] - points[i - 1]).norm();
    vertices.emplace_back(static_cast<float>(points[i].x()), static_cast<float>(points[i].y()),
                          static_cast<float>(points[i].z()), static_cast<float>(radii[i]));
    along.push_back(static_cast<float>(distance));
  }
  for (int i = 0; i + 1 < n; ++i) {
    segments.push_back(first + i);
    uint8_t f = 0;
    if (i > 0) f |= RTC_CURVE_FLAG_NEIGHBOR_LEFT;
    if (i + 2 < n) f |= RTC_CURVE_FLAG_NEIGHBOR_RIGHT;
    flags.push_back(f);
  }
}

TriangleMesh GroundMesh(const Eigen::Vector2d& center, double half_size_m) {
  TriangleMesh mesh;
  const float cx = static_cast<float>(center.x());
  const float cy = static_cast<float>(center.y());
  const float h = static_cast<float>(half_size_m);
  mesh.vertices = {
      {cx - h, cy - h, 0}, {cx + h, cy - h, 0}, {cx + h, cy + h, 0}, {cx - h, cy + h, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  return mesh;
}

TriangleMesh HedgeRingMesh(const Eigen::Vector2d& center, double radius_m, double height_m,
                           uint64_t seed) {
  // About 10 cm facets around, 5 rows up; the radius and the top edge wander by a few decimetres.
  TriangleMesh mesh;
  const int around = std::max(16, static_cast<int>(2.0 * std::numbers::pi * radius_m / 0.1));
  const int rows = 5;
  for (int j = 0; j <= rows; ++j) {
    for (int i = 0; i < around; ++i) {
      const double a = 2.0 * std::numbers::pi * i / around;
      const double along = a * radius_m;
      const double z_fraction = static_cast<double>(j) / rows;
      const double top = height_m * (0.9 + 0.2 * FractalNoise(along / 0.8, 0.5, seed + 5, 2,
                                                              std::max(1, around / 8)));
      const double bump =
          0.35 *
          (FractalNoise(along / 0.6, z_fraction * 3.0, seed + 7, 3, std::max(1, around / 6)) - 0.5);
      const double r = radius_m + bump;
      mesh.vertices.emplace_back(static_cast<float>(center.x() + r * std::cos(a)),
                                 static_cast<float>(center.y() + r * std::sin(a)),
                                 static_cast<float>(z_fraction * top));
    }
  }
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < around; ++i) {
      const int a = j * around + i;
      const int b = j * around + (i + 1) % around;
      const int c = a + around;
      const int d = b + around;
      mesh.triangles.emplace_back(a, b, d);
      mesh.triangles.emplace_back(a, d, c);
    }
  }
  return mesh;
}

TriangleMesh BoxMesh(const SceneBox& box) {
  TriangleMesh mesh;
  const Eigen::Matrix3d r = Eigen::AngleAxisd(box.yaw_rad, Eigen::Vector3d::UnitZ()).matrix();
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1);
    mesh.vertices.push_back((box.center + r * corner.cwiseProduct(box.half_extent)).cast<float>());
  }
  // Two triangles per face; winding does not matter (the renderer faces normals to the ray).
  const int faces[12][3] = {{0, 1, 3}, {0, 3, 2}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                            {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 3, 7}, {1, 7, 5}};
  for (const auto& f : faces) mesh.triangles.emplace_back(f[0], f[1], f[2]);
  return mesh;
}

CurveSet PostCurves(const ScenePost& post) {
  CurveSet curves;
  // Start below the ground so the bottom cap is hidden.
  curves.AddPolyline({Eigen::Vector3d(post.base.x(), post.base.y(), -0.1),
                      Eigen::Vector3d(post.base.x(), post.base.y(), post.height_m)},
                     {post.radius_m, post.radius_m});
  return curves;
}

CurveSet ShrubCurves(const SceneShrub& shrub) {
  CurveSet curves;
  std::mt19937_64 random(shrub.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d root(shrub.center.x(), shrub.center.y(), 0.0);
  for (int t = 0; t < shrub.twigs; ++t) {
    // A stem from the root to a point of the shrub's upper half, bending a little outwards.
    const double azimuth = 2.0 * std::numbers::pi * unit(random);
    const double elevation = 0.15 + 1.3 * unit(random);
    const double reach = shrub.radius_m * (0.6 + 0.4 * unit(random));
    const Eigen::Vector3d direction(std::cos(azimuth) * std::cos(elevation),
                                    std::sin(azimuth) * std::cos(elevation), std::sin(elevation));
    const Eigen::Vector3d tip = shrub.center + reach * direction;
    const Eigen::Vector3d wobble(unit(random) - 0.5, unit(random) - 0.5, unit(random) - 0.5);
    std::vector<Eigen::Vector3d> points;
    std::vector<double> radii;
    const int n = 6;
    for (int i = 0; i < n; ++i) {
      const double s = static_cast<double>(i) / (n - 1);
      points.push_back(root + s * (tip - root) + 0.1 * shrub.radius_m * std::sin(3.0 * s) * wobble);
      radii.push_back(0.008 * (1.0 - s) + 0.002 * s);
    }
    curves.AddPolyline(points, radii);
  }
  return curves;
}

}  // namespace simtree::synth
