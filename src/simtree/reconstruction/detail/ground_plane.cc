#include "simtree/reconstruction/detail/ground_plane.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <utility>

#include <Eigen/Geometry>

#include "simtree/core/option_checks.h"
#include "simtree/reconstruction/detail/cloud_preparation.h"

namespace simtree::reconstruction {

namespace {

// Share of `plane` points with standing points in their own or a neighbouring cell of a
// horizontal grid of `cell` metres. A cell counts with a few points: stray returns (sunlight,
// flying pixels) over open ground do not cover it.
double CoveredShare(const std::vector<Eigen::Vector3d>& plane,
                    const std::vector<Eigen::Vector3d>& standing, double cell) {
  if (plane.empty()) return 0.0;
  auto key = [cell](double x, double y) {
    const auto ix = static_cast<int64_t>(std::floor(x / cell));
    const auto iy = static_cast<int64_t>(std::floor(y / cell));
    return std::pair<int64_t, int64_t>(ix, iy);
  };
  constexpr int kMinPointsPerCell = 4;
  std::map<std::pair<int64_t, int64_t>, int> counts;
  for (const Eigen::Vector3d& p : standing) ++counts[key(p.x(), p.y())];
  std::set<std::pair<int64_t, int64_t>> occupied;
  for (const auto& [cell_key, count] : counts) {
    if (count >= kMinPointsPerCell) occupied.insert(cell_key);
  }
  const size_t stride = std::max<size_t>(1, plane.size() / 20000);
  size_t covered = 0, counted = 0;
  for (size_t k = 0; k < plane.size(); k += stride, ++counted) {
    const auto [ix, iy] = key(plane[k].x(), plane[k].y());
    bool hit = false;
    for (int dx = -1; dx <= 1 && !hit; ++dx) {
      for (int dy = -1; dy <= 1 && !hit; ++dy) hit = occupied.count({ix + dx, iy + dy}) > 0;
    }
    covered += hit;
  }
  return static_cast<double>(covered) / static_cast<double>(counted);
}

// The low points the ground is searched among: the subset hypotheses are scored on and the
// lowest quarter they are drawn from.
struct LowPoints {
  std::vector<int> low;     // within the lowest search_share of the cloud's height
  std::vector<int> scored;  // an even subset of `low`, every `stride`-th
  size_t stride = 1;
  std::vector<int> lowest;  // the lowest quarter of `low`
};

// Nothing when fewer than min_points are low.
std::optional<LowPoints> SelectLowPoints(std::span<const Eigen::Vector3d> points,
                                         const GroundOptions& options) {
  // Heights by quantile: a few stray returns far below the ground (sunlight, flying pixels) or
  // above the crown must not decide where the ground is searched for.
  std::vector<double> z(points.size());
  for (size_t i = 0; i < points.size(); ++i) z[i] = points[i].z();
  const size_t trim = points.size() / 500;
  std::nth_element(z.begin(), z.begin() + trim, z.end());
  const double z_low = z[trim];
  std::nth_element(z.begin(), z.end() - 1 - trim, z.end());
  const double z_high = z[z.size() - 1 - trim];
  const double z_search = z_low + options.search_share * (z_high - z_low);
  LowPoints out;
  for (size_t i = 0; i < points.size(); ++i) {
    if (points[i].z() <= z_search) out.low.push_back(static_cast<int>(i));
  }
  if (static_cast<int>(out.low.size()) < options.min_points) return std::nullopt;

  // Scoring every low point of a scene cloud (mostly ground) is wasteful: an even subset decides.
  out.stride = std::max<size_t>(1, out.low.size() / std::max(1, options.max_scored_points));
  for (size_t k = 0; k < out.low.size(); k += out.stride) out.scored.push_back(out.low[k]);

  // Hypotheses from the lowest quarter of the low points: the ground is the lowest surface, and
  // where a capture sees little of it (aimed at a tall crown) boxes and stems outnumber it.
  out.lowest = out.low;
  const size_t quarter = std::max<size_t>(3, out.lowest.size() / 4);
  std::nth_element(out.lowest.begin(), out.lowest.begin() + (quarter - 1), out.lowest.end(),
                   [&](int a, int b) { return points[a].z() < points[b].z(); });
  out.lowest.resize(quarter);
  return out;
}

struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // upwards
  double offset = 0.0;                                // normal . p + offset = 0
  size_t inliers = 0;                                 // scored points within the tolerance
};

// Seeded RANSAC: planes through three of the lowest points, within the tilt limit, scored by
// their inliers among the scored points.
Plane FitLowestPlane(std::span<const Eigen::Vector3d> points, const LowPoints& low,
                     const GroundOptions& options, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<size_t> pick(0, low.lowest.size() - 1);
  const double cos_tilt = std::cos(options.max_tilt_rad);
  Plane best;
  for (int it = 0; it < options.iterations; ++it) {
    const Eigen::Vector3d& a = points[low.lowest[pick(rng)]];
    const Eigen::Vector3d& b = points[low.lowest[pick(rng)]];
    const Eigen::Vector3d& c = points[low.lowest[pick(rng)]];
    Eigen::Vector3d normal = (b - a).cross(c - a);
    if (normal.norm() < 1e-9) continue;
    normal.normalize();
    if (normal.z() < 0) normal = -normal;
    if (normal.z() < cos_tilt) continue;
    const double offset = -normal.dot(a);
    size_t count = 0;
    for (const int i : low.scored)
      count += std::abs(normal.dot(points[i]) + offset) <= options.tolerance_m;
    if (count > best.inliers) best = {normal, offset, count};
  }
  return best;
}

// What tells ground from the bottom of a segmented trunk: the width of the plane's inliers, the
// width of what stands just above them, the share of the plane covered by it, and whether the
// plane reaches out around it.
struct GroundShape {
  double plane_width_m = 0.0;
  double standing_width_m = 0.0;
  double covered_share = 0.0;
  bool reaches_around = true;
};

GroundShape MeasureGroundShape(std::span<const Eigen::Vector3d> points, std::span<const int> low,
                               const Plane& plane, const GroundOptions& options) {
  std::vector<Eigen::Vector3d> on_plane, above;
  for (const int i : low) {
    const double h = plane.normal.dot(points[i]) + plane.offset;
    if (std::abs(h) <= options.tolerance_m) on_plane.push_back(points[i]);
    if (h > 4 * options.tolerance_m && h < 4 * options.tolerance_m + 0.3) {
      above.push_back(points[i]);
    }
  }
  const Eigen::Vector3d plane_extent = TrimmedExtent(on_plane, 0.02);
  const Eigen::Vector3d above_extent = TrimmedExtent(above, 0.02);
  GroundShape shape;
  shape.plane_width_m = std::min(plane_extent.x(), plane_extent.y());
  shape.standing_width_m = std::max(above_extent.x(), above_extent.y());
  // A plane through the bottom of a segmented trunk is a ring with wood right above it; ground is
  // mostly open: few of its points have anything standing on them (a trunk, a box, a post).
  shape.covered_share = CoveredShare(on_plane, above, std::max(2.0 * options.tolerance_m, 0.02));
  // Ground reaches out around what stands on it: plane points in at least two quadrants around
  // its centre (a capture aimed at a tall crown sees the ground on one or two sides only).
  if (!above.empty()) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : above) centre += p;
    centre /= above.size();
    int quadrant_points[4] = {0, 0, 0, 0};
    for (const Eigen::Vector3d& p : on_plane) {
      ++quadrant_points[(p.x() > centre.x() ? 1 : 0) + (p.y() > centre.y() ? 2 : 0)];
    }
    const int min_share = static_cast<int>(on_plane.size() / 20);
    shape.reaches_around = std::count_if(quadrant_points, quadrant_points + 4,
                                         [&](int c) { return c > min_share; }) >= 2;
  }
  return shape;
}

// How high above the plane the ground reaches: a range camera sees the far ground noisier than
// the tolerance, so the ground's own spread (a robust sigma of the heights near the plane, where
// ground dominates) decides, within [1, 4] tolerances.
double GroundClearance(std::span<const Eigen::Vector3d> points, std::span<const int> scored,
                       const GroundPlane& ground, const GroundOptions& options) {
  std::vector<double> near_heights;
  for (const int i : scored) {
    const double h = ground.HeightAbove(points[i]);
    if (std::abs(h) <= 4 * options.tolerance_m) near_heights.push_back(std::abs(h));
  }
  if (near_heights.empty()) return options.tolerance_m;
  const auto middle = near_heights.begin() + near_heights.size() / 2;
  std::nth_element(near_heights.begin(), middle, near_heights.end());
  return std::clamp(4.0 * 1.4826 * *middle, options.tolerance_m, 4 * options.tolerance_m);
}

}  // namespace

void GroundOptions::Validate() const {
  CheckPositive("tolerance_m", tolerance_m);
  CheckInRange("max_tilt_rad", max_tilt_rad, 0.0, M_PI / 2);
  CheckInRange("search_share", search_share, 0.0, 1.0);
  CheckNonNegative("min_width_m", min_width_m);
  CheckShare("max_covered_share", max_covered_share);
  CheckAtLeast("min_points", min_points, 3);
  CheckAtLeast("iterations", iterations, 1);
  CheckAtLeast("max_scored_points", max_scored_points, 1);
}

double GroundPlane::HeightAt(double x, double y) const {
  if (std::abs(normal.z()) < 1e-9) return 0.0;
  return -(normal.x() * x + normal.y() * y + offset) / normal.z();
}

GroundPlane FindGroundPlane(std::span<const Eigen::Vector3d> points, const GroundOptions& options,
                            uint64_t seed) {
  options.Validate();
  GroundPlane ground;
  ground.is_ground.assign(points.size(), 0);
  if (points.size() < 3) return ground;
  const std::optional<LowPoints> low = SelectLowPoints(points, options);
  if (!low) return ground;
  const Plane plane = FitLowestPlane(points, *low, options, seed);
  if (static_cast<int>(plane.inliers * low->stride) < options.min_points) return ground;
  // Wide and open enough? The measurements are kept also when the plane is rejected.
  const GroundShape shape = MeasureGroundShape(points, low->low, plane, options);
  ground.plane_width_m = shape.plane_width_m;
  ground.standing_width_m = shape.standing_width_m;
  ground.covered_share = shape.covered_share;
  if (shape.plane_width_m < options.min_width_m ||
      shape.covered_share > options.max_covered_share || !shape.reaches_around) {
    return ground;
  }
  ground.found = true;
  ground.normal = plane.normal;
  ground.offset = plane.offset;
  ground.clearance_m = GroundClearance(points, low->scored, ground, options);
  for (size_t i = 0; i < points.size(); ++i) {
    if (ground.HeightAbove(points[i]) <= ground.clearance_m) {
      ground.is_ground[i] = 1;
      ++ground.ground_points;
    }
  }
  return ground;
}

}  // namespace simtree::reconstruction
