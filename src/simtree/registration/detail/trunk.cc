#include "simtree/registration/detail/trunk.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <unordered_map>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "simtree/core/option_checks.h"
#include "simtree/core/statistics.h"

namespace simtree::registration {
namespace {

// A group of slice points in the slice plane.
struct Group {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  double width = 0.0;  // largest extent across the slice plane
  std::vector<int> members;
};

int FindRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

// Single-linkage groups of 2-D points at `link` (a grid of cells `link` wide finds neighbours).
std::vector<Group> GroupSlice(const std::vector<Eigen::Vector2d>& points, double link) {
  const int n = static_cast<int>(points.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto key = [&](int cx, int cy) { return (static_cast<int64_t>(cx) << 32) ^ (cy & 0xffffffffLL); };
  std::unordered_map<int64_t, std::vector<int>> cells;
  for (int i = 0; i < n; ++i) {
    cells[key(static_cast<int>(std::floor(points[i].x() / link)),
              static_cast<int>(std::floor(points[i].y() / link)))]
        .push_back(i);
  }
  const double link2 = link * link;
  for (int i = 0; i < n; ++i) {
    const int cx = static_cast<int>(std::floor(points[i].x() / link));
    const int cy = static_cast<int>(std::floor(points[i].y() / link));
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        auto it = cells.find(key(cx + dx, cy + dy));
        if (it == cells.end()) continue;
        for (int j : it->second) {
          if (j <= i || (points[i] - points[j]).squaredNorm() > link2) continue;
          parent[FindRoot(parent, i)] = FindRoot(parent, j);
        }
      }
    }
  }
  std::unordered_map<int, int> group_of_root;
  std::vector<Group> groups;
  for (int i = 0; i < n; ++i) {
    const int root = FindRoot(parent, i);
    auto [it, inserted] = group_of_root.emplace(root, static_cast<int>(groups.size()));
    if (inserted) groups.emplace_back();
    groups[it->second].members.push_back(i);
  }
  for (Group& g : groups) {
    Eigen::Vector2d lo = points[g.members[0]], hi = lo;
    for (int i : g.members) {
      g.centroid += points[i];
      lo = lo.cwiseMin(points[i]);
      hi = hi.cwiseMax(points[i]);
    }
    g.centroid /= static_cast<double>(g.members.size());
    g.width = (hi - lo).maxCoeff();
  }
  return groups;
}

// The cloud cut into slices across up, each slice's points in the slice plane (e1, e2).
struct Slices {
  Eigen::Vector3d up, e1, e2;  // unit
  double bottom = 0.0;         // height along up where the first slice starts
  double height = 0.0;         // of a slice
  std::vector<std::vector<Eigen::Vector2d>> points;

  int count() const { return static_cast<int>(points.size()); }
  // A slice-plane point of slice `s` in 3-D, at the slice's middle height.
  Eigen::Vector3d Centre(const Eigen::Vector2d& c, int s) const {
    return Eigen::Vector3d(c.x() * e1 + c.y() * e2 + (bottom + (s + 0.5) * height) * up);
  }
};

Slices SliceCloud(const open3d::geometry::PointCloud& cloud, const Eigen::Vector3d& up,
                  double slice_height_m) {
  Slices slices;
  slices.up = up.normalized();
  slices.e1 = slices.up.unitOrthogonal();
  slices.e2 = slices.up.cross(slices.e1);
  slices.height = slice_height_m;
  // Heights from a robust bottom (the lowest 0.5% may be noise).
  std::vector<double> heights(cloud.points_.size());
  for (size_t i = 0; i < heights.size(); ++i) heights[i] = cloud.points_[i].dot(slices.up);
  std::vector<double> sorted = heights;
  const size_t low_index = sorted.size() / 200;
  std::nth_element(sorted.begin(), sorted.begin() + low_index, sorted.end());
  slices.bottom = sorted[low_index];
  const double top = *std::max_element(heights.begin(), heights.end());
  const int count = static_cast<int>((top - slices.bottom) / slice_height_m) + 1;
  slices.points.resize(count);
  for (size_t i = 0; i < heights.size(); ++i) {
    if (heights[i] < slices.bottom) continue;
    const int s =
        std::min(count - 1, static_cast<int>((heights[i] - slices.bottom) / slice_height_m));
    slices.points[s].emplace_back(cloud.points_[i].dot(slices.e1), cloud.points_[i].dot(slices.e2));
  }
  return slices;
}

// The groups of a slice that continue the trunk from the slice below (its centroid and width).
std::vector<const Group*> Continuations(const std::vector<Group>& groups,
                                        const Eigen::Vector2d& centroid, double width,
                                        double link) {
  std::vector<const Group*> out;
  for (const Group& g : groups) {
    if ((g.centroid - centroid).norm() < 0.5 * (width + g.width) + link) out.push_back(&g);
  }
  return out;
}

// True when a slice's continuation is not a single trunk-like group: two arms, or one group
// much wider than the trunk.
bool IsSplit(const std::vector<const Group*>& next, double trunk_width, double link,
             const TrunkOptions& options) {
  size_t total = 0;
  for (const Group* g : next) total += g->members.size();
  int arms = 0;
  for (const Group* g : next) {
    if (g->members.size() >= options.min_arm_share * total) ++arms;
  }
  if (arms >= 2) return true;
  for (const Group* g : next) {
    if (g->members.size() >= options.min_arm_share * total &&
        g->width > options.widen_factor * trunk_width + link) {
      return true;
    }
  }
  return false;
}

// The dominant group of a continuation (the one the trunk follows).
const Group* Largest(const std::vector<const Group*>& next) {
  return *std::max_element(next.begin(), next.end(), [](const Group* a, const Group* b) {
    return a->members.size() < b->members.size();
  });
}

// A split at slice `s` is the branching point when the next confirm_slices slices stay split
// (or empty): a side twig or a knot does not end the trunk.
bool SplitHolds(const Slices& slices, int s, const Eigen::Vector2d& centroid, double width,
                double trunk_width, double link, const TrunkOptions& options) {
  int confirmed = 0;
  for (int c = 1; c <= options.confirm_slices && s + c < slices.count(); ++c) {
    const std::vector<Group> later = GroupSlice(slices.points[s + c], link);
    const auto later_next = Continuations(later, centroid, width + 2 * c * slices.height, link);
    if (later_next.empty() || IsSplit(later_next, trunk_width, link, options)) ++confirmed;
  }
  return confirmed >= options.confirm_slices;
}

// The trunk followed up the slices: its slices' centroids and widths, from the first slice that
// holds it to the last before it forks (or ends).
struct TrunkTrace {
  std::vector<Eigen::Vector3d> centres;  // in 3-D
  std::vector<double> widths;
  int first = -1;  // -1: no points at the bottom
  int last = -1;
  bool fork = false;
};

TrunkTrace FollowTrunk(const Slices& slices, double link, const TrunkOptions& options) {
  TrunkTrace trace;
  // The trunk starts as the largest group of the first slices.
  Group start;
  for (int s = 0; s < std::min(slices.count(), 3); ++s) {
    if (slices.points[s].size() < 3) continue;
    std::vector<Group> groups = GroupSlice(slices.points[s], link);
    start = *std::max_element(groups.begin(), groups.end(), [](const Group& a, const Group& b) {
      return a.members.size() < b.members.size();
    });
    trace.first = s;
    break;
  }
  if (trace.first < 0) return trace;
  trace.centres.push_back(slices.Centre(start.centroid, trace.first));
  trace.widths.push_back(start.width);
  Eigen::Vector2d centroid = start.centroid;
  double width = start.width;
  trace.last = trace.first;
  int gap = 0;
  for (int s = trace.first + 1; s < slices.count(); ++s) {
    const std::vector<Group> groups = GroupSlice(slices.points[s], link);
    const auto next = Continuations(groups, centroid, width, link);
    if (next.empty()) {
      if (++gap > options.max_gap_slices) break;
      continue;
    }
    gap = 0;
    const double trunk_width = UpperMedian(trace.widths);
    if (IsSplit(next, trunk_width, link, options) && trace.centres.size() >= 2 &&
        SplitHolds(slices, s, centroid, width, trunk_width, link, options)) {
      trace.fork = true;
      break;
    }
    const Group* g = Largest(next);
    centroid = g->centroid;
    width = g->width;
    trace.centres.push_back(slices.Centre(centroid, s));
    trace.widths.push_back(width);
    trace.last = s;
  }
  return trace;
}

// The trunk's axis through the slices' centroids (least squares, pointing up), with its base
// and branching point on it.
TrunkFit FitTrunkAxis(const Slices& slices, const TrunkTrace& trace, double length_m) {
  const Eigen::Vector3d& up = slices.up;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& c : trace.centres) mean += c;
  mean /= static_cast<double>(trace.centres.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& c : trace.centres) covariance += (c - mean) * (c - mean).transpose();
  Eigen::Vector3d axis = up;
  if (trace.centres.size() >= 4) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
    axis = solver.eigenvectors().col(2).normalized();
    if (axis.dot(up) < 0) axis = -axis;
    // A trunk leaning more than 30 degrees is not trusted for its axis.
    if (axis.dot(up) < std::cos(30.0 * std::numbers::pi / 180.0)) axis = up;
  }
  auto on_axis = [&](double height) {
    const double along = (height - mean.dot(up)) / axis.dot(up);
    return Eigen::Vector3d(mean + along * axis);
  };
  TrunkFit fit;
  fit.axis = axis;
  fit.base = on_axis(slices.bottom + trace.first * slices.height);
  fit.branch_point = on_axis(slices.bottom + (trace.last + 1) * slices.height);
  fit.visible_width_m = UpperMedian(trace.widths);
  fit.length_m = length_m;
  fit.fork_found = trace.fork;
  fit.slices = static_cast<int>(trace.centres.size());
  return fit;
}

}  // namespace

void TrunkOptions::Validate() const {
  CheckPositive("slice_height_m", slice_height_m);
  CheckNonNegative("link_distance_m", link_distance_m);
  CheckNonNegative("min_trunk_length_m", min_trunk_length_m);
  CheckPositive("widen_factor", widen_factor);
  CheckShare("min_arm_share", min_arm_share);
  CheckNonNegative("confirm_slices", confirm_slices);
  CheckNonNegative("max_gap_slices", max_gap_slices);
}

void CylinderFitOptions::Validate() const {
  CheckNonNegative("margin_m", margin_m);
  CheckAtLeast("iterations", iterations, 1);
  CheckPositive("huber_m", huber_m);
  CheckAtLeast("min_points", min_points, 5);
  CheckNonNegative("min_length_m", min_length_m);
}

void KeyRegionOptions::Validate() const {
  CheckNonNegative("radius_m", radius_m);
  CheckShare("height_share", height_share);
  CheckNonNegative("min_radius_m", min_radius_m);
  CheckOrdered("min_radius_m", min_radius_m, "max_radius_m", max_radius_m);
}

std::optional<TrunkFit> FindTrunk(const open3d::geometry::PointCloud& cloud,
                                  const Eigen::Vector3d& up, double spacing_m,
                                  const TrunkOptions& options, std::string* why) {
  options.Validate();
  auto fail = [&](const std::string& reason) -> std::optional<TrunkFit> {
    if (why) *why = reason;
    return std::nullopt;
  };
  if (cloud.points_.size() < 20) return fail("too few points to hold a trunk");
  const double link =
      options.link_distance_m > 0 ? options.link_distance_m : std::max(0.02, 3.0 * spacing_m);
  const Slices slices = SliceCloud(cloud, up, options.slice_height_m);
  const TrunkTrace trace = FollowTrunk(slices, link, options);
  if (trace.first < 0) return fail("no points at the bottom of the view");
  const double length = (trace.last - trace.first + 1) * slices.height;
  if (length < options.min_trunk_length_m || trace.centres.size() < 3) {
    return fail(
        fmt::format("no trunk: the bottom of the view holds no upright stem of {:.2f} m "
                    "or more (found {:.2f} m)",
                    options.min_trunk_length_m, length));
  }
  return FitTrunkAxis(slices, trace, length);
}

namespace {

// Gauss-Newton on (axis point across the axis: 2, axis direction: 2, radius: 1), each step in
// the frame of the current axis; residual = distance to the axis - radius, Huber-weighted.
bool FitCylinder(const std::vector<Eigen::Vector3d>& points, const CylinderFitOptions& options,
                 Eigen::Vector3d& c, Eigen::Vector3d& d, double& r) {
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    const Eigen::Vector3d e1 = d.unitOrthogonal();
    const Eigen::Vector3d e2 = d.cross(e1);
    Eigen::Matrix<double, 5, 5> jtj = Eigen::Matrix<double, 5, 5>::Zero();
    Eigen::Matrix<double, 5, 1> jtr = Eigen::Matrix<double, 5, 1>::Zero();
    for (const auto& p : points) {
      const Eigen::Vector3d v = p - c;
      const double along = v.dot(d);
      const Eigen::Vector3d across = v - along * d;
      const double distance = across.norm();
      if (distance < 1e-9) continue;
      const Eigen::Vector3d u = across / distance;
      const double residual = distance - r;
      // d(distance)/d(c) = -u across the axis; tilting d towards e moves the axis by along * e.
      Eigen::Matrix<double, 5, 1> j;
      j << -u.dot(e1), -u.dot(e2), -along * u.dot(e1), -along * u.dot(e2), -1.0;
      const double w =
          std::abs(residual) <= options.huber_m ? 1.0 : options.huber_m / std::abs(residual);
      jtj += w * j * j.transpose();
      jtr += w * j * residual;
    }
    const Eigen::Matrix<double, 5, 1> step = jtj.ldlt().solve(-jtr);
    if (!step.allFinite()) return false;
    c += step(0) * e1 + step(1) * e2;
    d = (d + step(2) * e1 + step(3) * e2).normalized();
    r += step(4);
    if (step.norm() < 1e-6) break;
  }
  return std::isfinite(r);
}

double Residual(const Eigen::Vector3d& p, const Eigen::Vector3d& c, const Eigen::Vector3d& d,
                double r) {
  const Eigen::Vector3d v = p - c;
  return (v - v.dot(d) * d).norm() - r;
}

}  // namespace

std::optional<TrunkCylinder> FitTrunkCylinder(const open3d::geometry::PointCloud& cloud,
                                              const TrunkFit& trunk,
                                              const CylinderFitOptions& options) {
  options.Validate();
  // The trunk's points: between base and branching point (less the margins), near the axis.
  const double lo = options.margin_m;
  double hi = trunk.length_m - options.margin_m;
  if (hi - lo < options.min_length_m) return std::nullopt;
  const double reach = trunk.visible_width_m + 0.03;
  std::vector<Eigen::Vector3d> candidates;
  std::vector<double> heights;
  for (const auto& p : cloud.points_) {
    const Eigen::Vector3d v = p - trunk.base;
    const double along = v.dot(trunk.axis);
    if (along < lo || along > hi) continue;
    if ((v - along * trunk.axis).norm() > reach) continue;
    candidates.push_back(p);
    heights.push_back(along);
  }
  // Start behind the visible surface: the camera (the origin) sees the near half of the trunk,
  // whose centroid lies 2r/pi in front of the axis.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : candidates) mean += p;
  mean /= std::max<double>(1.0, candidates.size());
  const Eigen::Vector3d d0 = trunk.axis;
  const double r0 = 0.5 * trunk.visible_width_m;
  const Eigen::Vector3d away = (mean - mean.dot(d0) * d0).normalized();
  const Eigen::Vector3d c0 =
      trunk.base + 0.5 * (lo + hi) * d0 + away * (2.0 / std::numbers::pi) * r0;

  // Fit the lower half, then grow upwards band by band while the points keep fitting (a fork the
  // slices did not catch, one arm hidden behind the other, stops it), and refit on all of it.
  Eigen::Vector3d c, d;
  double r = 0.0;
  std::vector<Eigen::Vector3d> points;
  auto fit_below = [&](double top) {
    points.clear();
    for (size_t i = 0; i < candidates.size(); ++i) {
      if (heights[i] <= top) points.push_back(candidates[i]);
    }
    if (static_cast<int>(points.size()) < options.min_points) return false;
    c = c0;
    d = d0;
    r = r0;
    return FitCylinder(points, options, c, d, r);
  };
  const double band = 0.05;
  double top = std::min(hi, lo + std::max(options.min_length_m, 0.5 * (hi - lo)));
  if (!fit_below(top)) return std::nullopt;
  auto band_median = [&](double from, double to) {
    std::vector<double> v;
    for (size_t i = 0; i < candidates.size(); ++i) {
      if (heights[i] > from && heights[i] <= to)
        v.push_back(std::abs(Residual(candidates[i], c, d, r)));
    }
    if (v.empty()) return -1.0;
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  const double typical = std::max(band_median(lo, top), 1e-3);
  while (top + 0.5 * band < hi) {
    const double next = std::min(hi, top + band);
    const double m = band_median(top, next);
    if (m > std::max(2.0 * typical, 0.5 * options.huber_m)) break;
    top = next;
  }
  hi = top;
  if (!fit_below(hi)) return std::nullopt;
  if (d.dot(trunk.axis) < 0) d = -d;
  if (!(r > 0.15 * trunk.visible_width_m && r < 1.5 * trunk.visible_width_m)) return std::nullopt;
  TrunkCylinder cylinder;
  cylinder.axis = d;
  cylinder.radius_m = r;
  // Centre the axis point on the fitted points' middle height.
  double sum = 0.0, squared = 0.0;
  for (const auto& p : points) {
    sum += (p - c).dot(d);
    const double residual = Residual(p, c, d, r);
    squared += residual * residual;
  }
  cylinder.point = c + (sum / static_cast<double>(points.size())) * d;
  cylinder.half_length_m = 0.5 * (hi - lo);
  cylinder.rms_m = std::sqrt(squared / static_cast<double>(points.size()));
  cylinder.points = static_cast<int>(points.size());
  return cylinder;
}

KeyRegion KeyRegionOf(const TrunkFit& trunk, const open3d::geometry::PointCloud& cloud,
                      const Eigen::Vector3d& up, const KeyRegionOptions& options) {
  options.Validate();
  KeyRegion region;
  region.center = trunk.branch_point;
  if (options.radius_m > 0) {
    region.radius_m = options.radius_m;
    return region;
  }
  double top = -std::numeric_limits<double>::infinity();
  for (const auto& p : cloud.points_) top = std::max(top, p.dot(up));
  const double height = top - trunk.base.dot(up);
  region.radius_m =
      std::clamp(options.height_share * height, options.min_radius_m, options.max_radius_m);
  return region;
}

std::vector<size_t> PointsInside(const open3d::geometry::PointCloud& cloud,
                                 const KeyRegion& region) {
  std::vector<size_t> inside;
  const double r2 = region.radius_m * region.radius_m;
  for (size_t i = 0; i < cloud.points_.size(); ++i) {
    if ((cloud.points_[i] - region.center).squaredNorm() <= r2) inside.push_back(i);
  }
  return inside;
}

}  // namespace simtree::registration
