#include "simtree/reconstruction/ground_plane.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "simtree/reconstruction/cloud_preparation.h"

namespace simtree {

double GroundPlane::HeightAt(double x, double y) const {
  if (std::abs(normal.z()) < 1e-9) return 0.0;
  return -(normal.x() * x + normal.y() * y + offset) / normal.z();
}

GroundPlane FindGroundPlane(std::span<const Eigen::Vector3d> points, const GroundOptions& options) {
  GroundPlane ground;
  ground.is_ground.assign(points.size(), 0);
  if (points.size() < 3) return ground;
  double z_low = std::numeric_limits<double>::infinity(), z_high = -z_low;
  for (const Eigen::Vector3d& p : points) {
    z_low = std::min(z_low, p.z());
    z_high = std::max(z_high, p.z());
  }
  const double z_search = z_low + options.search_share * (z_high - z_low);
  std::vector<int> low;
  for (size_t i = 0; i < points.size(); ++i) {
    if (points[i].z() <= z_search) low.push_back(static_cast<int>(i));
  }
  if (static_cast<int>(low.size()) < options.min_points) return ground;

  std::mt19937_64 rng(options.seed);
  std::uniform_int_distribution<size_t> pick(0, low.size() - 1);
  const double cos_tilt = std::cos(options.max_tilt_rad);
  size_t best_count = 0;
  Eigen::Vector3d best_normal = Eigen::Vector3d::UnitZ();
  double best_offset = 0.0;
  for (int it = 0; it < options.iterations; ++it) {
    const Eigen::Vector3d& a = points[low[pick(rng)]];
    const Eigen::Vector3d& b = points[low[pick(rng)]];
    const Eigen::Vector3d& c = points[low[pick(rng)]];
    Eigen::Vector3d normal = (b - a).cross(c - a);
    if (normal.norm() < 1e-9) continue;
    normal.normalize();
    if (normal.z() < 0) normal = -normal;
    if (normal.z() < cos_tilt) continue;
    const double offset = -normal.dot(a);
    size_t count = 0;
    for (const int i : low)
      count += std::abs(normal.dot(points[i]) + offset) <= options.tolerance_m;
    if (count > best_count) {
      best_count = count;
      best_normal = normal;
      best_offset = offset;
    }
  }
  if (static_cast<int>(best_count) < options.min_points) return ground;

  // Wide enough? Compare the plane's inliers with what stands just above it.
  std::vector<Eigen::Vector3d> on_plane, above;
  for (const int i : low) {
    const double h = best_normal.dot(points[i]) + best_offset;
    if (std::abs(h) <= options.tolerance_m) on_plane.push_back(points[i]);
    if (h > 4 * options.tolerance_m && h < 4 * options.tolerance_m + 0.3) {
      above.push_back(points[i]);
    }
  }
  const Eigen::Vector3d plane_extent = TrimmedExtent(on_plane, 0.02);
  const Eigen::Vector3d above_extent = TrimmedExtent(above, 0.02);
  const double plane_width = std::min(plane_extent.x(), plane_extent.y());
  const double trunk_width = std::max(above_extent.x(), above_extent.y());
  if (plane_width < options.min_width_m ||
      (!above.empty() && plane_width < options.width_over_trunk * trunk_width)) {
    return ground;
  }
  // Ground surrounds the trunk: plane points in at least three quadrants around what stands on it.
  if (!above.empty()) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : above) centre += p;
    centre /= above.size();
    int quadrant_points[4] = {0, 0, 0, 0};
    for (const Eigen::Vector3d& p : on_plane) {
      ++quadrant_points[(p.x() > centre.x() ? 1 : 0) + (p.y() > centre.y() ? 2 : 0)];
    }
    const int min_share = static_cast<int>(on_plane.size() / 20);
    if (std::count_if(quadrant_points, quadrant_points + 4, [&](int c) { return c > min_share; }) <
        3) {
      return ground;
    }
  }
  ground.found = true;
  ground.normal = best_normal;
  ground.offset = best_offset;
  for (size_t i = 0; i < points.size(); ++i) {
    if (ground.HeightAbove(points[i]) <= options.tolerance_m) {
      ground.is_ground[i] = 1;
      ++ground.ground_points;
    }
  }
  return ground;
}

}  // namespace simtree
