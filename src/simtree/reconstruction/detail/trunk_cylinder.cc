#include "simtree/reconstruction/detail/trunk_cylinder.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "simtree/core/option_checks.h"
#include "simtree/core/statistics.h"
#include "simtree/reconstruction/detail/local_geometry.h"
#include "simtree/reconstruction/detail/point_index.h"

namespace simtree::reconstruction {
namespace {

std::vector<Eigen::Vector3d> EstimateNormals(std::span<const Eigen::Vector3d> points,
                                             int neighbours) {
  const PointIndex index(points);
  std::vector<Eigen::Vector3d> normals(points.size(), Eigen::Vector3d::Zero());
  std::vector<int> near;
  std::vector<double> d2;
  for (size_t i = 0; i < points.size(); ++i) {
    index.Nearest(points[i], neighbours, near, d2);
    if (near.size() < 3) continue;
    Eigen::Vector3d mean;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(
        NeighbourhoodCovariance(points, near, &mean));
    normals[i] = eig.eigenvectors().col(0);
  }
  return normals;
}

// Cylinder through two oriented points: the axis is normal to both normals, and both normal lines
// cross it.
bool CylinderFromTwoPoints(const Eigen::Vector3d& p1, const Eigen::Vector3d& n1,
                           const Eigen::Vector3d& p2, const Eigen::Vector3d& n2, Cylinder* out) {
  Eigen::Vector3d axis = n1.cross(n2);
  if (axis.norm() < 0.2) return false;
  axis.normalize();
  if (axis.z() < 0) axis = -axis;
  // In the plane normal to the axis, intersect the two normal lines.
  Eigen::Vector3d e1, e2;
  PlaneBasis(axis, &e1, &e2);
  const Eigen::Vector2d a(p1.dot(e1), p1.dot(e2)), b(p2.dot(e1), p2.dot(e2));
  const Eigen::Vector2d da(n1.dot(e1), n1.dot(e2)), db(n2.dot(e1), n2.dot(e2));
  Eigen::Matrix2d m;
  m << da, -db;
  if (std::abs(m.determinant()) < 1e-6) return false;
  const Eigen::Vector2d st = m.colPivHouseholderQr().solve(b - a);
  const Eigen::Vector2d c = a + st[0] * da;
  out->axis = axis;
  out->point = c.x() * e1 + c.y() * e2 + axis * p1.dot(axis);
  out->radius = 0.5 * ((a - c).norm() + (b - c).norm());
  return std::isfinite(out->radius);
}

double MsacCost(const Cylinder& c, std::span<const Eigen::Vector3d> points,
                std::span<const int> subset, double threshold) {
  const double t2 = threshold * threshold;
  double cost = 0.0;
  for (const int i : subset) {
    const double e = c.AxisDistance(points[i]) - c.radius;
    cost += std::min(e * e, t2);
  }
  return cost;
}

// Gauss-Newton on the geometric residuals (distance to the axis minus radius), five parameters:
// two tilts of the axis, two shifts of its point, the radius.
Cylinder RefineCylinder(const Cylinder& start, std::span<const Eigen::Vector3d> points,
                        std::span<const int> inliers) {
  Cylinder c = start;
  if (inliers.size() < 8) return c;
  for (int iteration = 0; iteration < 10; ++iteration) {
    Eigen::Vector3d e1, e2;
    PlaneBasis(c.axis, &e1, &e2);
    auto make = [&](const Eigen::Matrix<double, 5, 1>& x) {
      Cylinder t;
      t.axis = (c.axis + x[0] * e1 + x[1] * e2).normalized();
      t.point = c.point + x[2] * e1 + x[3] * e2;
      t.radius = c.radius + x[4];
      return t;
    };
    Eigen::MatrixXd jacobian(inliers.size(), 5);
    Eigen::VectorXd residual(inliers.size());
    const Eigen::Matrix<double, 5, 1> zero = Eigen::Matrix<double, 5, 1>::Zero();
    for (size_t k = 0; k < inliers.size(); ++k) {
      residual[k] = c.AxisDistance(points[inliers[k]]) - c.radius;
    }
    const double h = 1e-6;
    for (int p = 0; p < 5; ++p) {
      Eigen::Matrix<double, 5, 1> dx = zero;
      dx[p] = h;
      const Cylinder moved = make(dx);
      for (size_t k = 0; k < inliers.size(); ++k) {
        jacobian(k, p) = (moved.AxisDistance(points[inliers[k]]) - moved.radius - residual[k]) / h;
      }
    }
    const Eigen::Matrix<double, 5, 1> step =
        (jacobian.transpose() * jacobian + 1e-9 * Eigen::Matrix<double, 5, 5>::Identity())
            .ldlt()
            .solve(-jacobian.transpose() * residual);
    if (!step.allFinite()) break;
    c = make(step);
    if (c.axis.z() < 0) c.axis = -c.axis;
    if (step.norm() < 1e-7) break;
  }
  return c;
}

std::vector<int> Inliers(const Cylinder& c, std::span<const Eigen::Vector3d> points,
                         double threshold) {
  std::vector<int> inliers;
  for (size_t i = 0; i < points.size(); ++i) {
    if (std::abs(c.AxisDistance(points[i]) - c.radius) <= threshold) {
      inliers.push_back(static_cast<int>(i));
    }
  }
  return inliers;
}

// Coordinates of `points` in the plane through `origin` spanned by e1, e2.
std::vector<Eigen::Vector2d> InPlane(std::span<const Eigen::Vector3d> points,
                                     const Eigen::Vector3d& origin, const Eigen::Vector3d& e1,
                                     const Eigen::Vector3d& e2) {
  std::vector<Eigen::Vector2d> q(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d d = points[i] - origin;
    q[i] = {d.dot(e1), d.dot(e2)};
  }
  return q;
}

// A circle per slice along the axis, each from every point of its slab near the axis (not only
// from what already fits the cylinder: a fork or a low branch must show), robust to the stray
// points in it.
std::vector<TrunkSlice> FitSlices(const Cylinder& c, const Eigen::Vector3d& base, double top,
                                  std::span<const Eigen::Vector3d> points, double threshold,
                                  const TrunkFitOptions& options) {
  const int slices = std::max(options.slices, 1);
  const double reach = 2.0 * c.radius + 3.0 * threshold;
  std::vector<std::vector<Eigen::Vector3d>> slab(slices);
  for (const Eigen::Vector3d& p : points) {
    const double t = (p - base).dot(c.axis);
    if (t < 0 || t > top || c.AxisDistance(p) > reach) continue;
    slab[std::min(slices - 1, static_cast<int>(t / top * slices))].push_back(p);
  }
  std::vector<TrunkSlice> out;
  for (int s = 0; s < slices; ++s) {
    TrunkSlice slice;
    slice.from_m = top * s / slices;
    slice.to_m = top * (s + 1) / slices;
    slice.points = static_cast<int>(slab[s].size());
    const Eigen::Vector3d origin = base + c.axis * 0.5 * (slice.from_m + slice.to_m);
    if (slice.points >= 6 &&
        FitCircleRobust(slab[s], origin, c.axis, threshold, &slice.centre, &slice.radius_m)) {
      slice.centre_offset_m = c.AxisDistance(slice.centre);
      const double slack = threshold;
      slice.agrees = std::abs(slice.radius_m - c.radius) <=
                         options.slice_radius_tolerance * c.radius + slack &&
                     slice.centre_offset_m <= options.slice_centre_tolerance * c.radius + slack;
    }
    out.push_back(slice);
  }
  return out;
}

// The cylinder the slice circles describe, when most of them agree with each other (radii within
// the tolerance of their median, centres on one line): axis through their centres, radius their
// median. False when they do not or too few fitted.
bool SliceConsensus(std::span<const TrunkSlice> slices, const Cylinder& c, double threshold,
                    const TrunkFitOptions& options, Cylinder* out) {
  std::vector<double> radii;
  for (const TrunkSlice& s : slices) {
    if (s.radius_m > 0) radii.push_back(s.radius_m);
  }
  if (radii.size() < 3) return false;
  const double radius = UpperMedian(radii);
  const double slack = threshold;
  std::vector<Eigen::Vector3d> centres;
  for (const TrunkSlice& s : slices) {
    if (s.radius_m > 0 &&
        std::abs(s.radius_m - radius) <= options.slice_radius_tolerance * radius + slack) {
      centres.push_back(s.centre);
    }
  }
  if (2 * centres.size() <= slices.size() || centres.size() < 3) return false;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : centres) mean += p;
  mean /= centres.size();
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : centres) scatter += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  Eigen::Vector3d axis = eig.eigenvectors().col(2);
  if (axis.dot(c.axis) < 0) axis = -axis;
  for (const Eigen::Vector3d& p : centres) {
    if ((p - mean).cross(axis).norm() > options.slice_centre_tolerance * radius + slack) {
      return false;
    }
  }
  if (axis.z() < std::cos(options.max_tilt_rad) || radius < options.min_radius_m ||
      radius > options.max_radius_m) {
    return false;
  }
  out->axis = axis;
  out->point = mean;
  out->radius = radius;
  return true;
}

// The MSAC cylinder: hypotheses through two points and their normals, within the tilt and radius
// limits, scored on a fixed random subset (the whole set when small) by the truncated squared
// distance. Nothing when no hypothesis is within the limits.
std::optional<Cylinder> MsacCylinder(std::span<const Eigen::Vector3d> points, double threshold,
                                     const TrunkFitOptions& options, uint64_t seed) {
  const std::vector<Eigen::Vector3d> normals = EstimateNormals(points, options.normal_neighbours);
  std::mt19937_64 rng(seed);
  const int n = static_cast<int>(points.size());
  std::vector<int> subset(n);
  for (int i = 0; i < n; ++i) subset[i] = i;
  std::shuffle(subset.begin(), subset.end(), rng);
  if (subset.size() > 1500) subset.resize(1500);
  std::uniform_int_distribution<int> pick(0, n - 1);
  const double cos_tilt = std::cos(options.max_tilt_rad);
  double best_cost = std::numeric_limits<double>::infinity();
  Cylinder best;
  for (int it = 0; it < options.iterations; ++it) {
    const int i = pick(rng), j = pick(rng);
    if (i == j || normals[i].isZero() || normals[j].isZero()) continue;
    Cylinder c;
    if (!CylinderFromTwoPoints(points[i], normals[i], points[j], normals[j], &c)) continue;
    if (c.axis.z() < cos_tilt || c.radius < options.min_radius_m ||
        c.radius > options.max_radius_m) {
      continue;
    }
    const double cost = MsacCost(c, points, subset, threshold);
    if (cost < best_cost) {
      best_cost = cost;
      best = c;
    }
  }
  if (!std::isfinite(best_cost)) return std::nullopt;
  return best;
}

// The fit of `start` to `kept`: refined on its inliers (not when it was rebuilt from slice
// circles, which measure it better), measured, and checked slice by slice; a rebuilt cylinder
// takes its radius from the slices across its own axis. Nothing when it leaves the tilt and
// radius limits.
std::optional<TrunkFit> MeasureCylinder(const Cylinder& start, bool rebuilt,
                                        std::span<const Eigen::Vector3d> kept, double base_height,
                                        double threshold, const TrunkFitOptions& options) {
  Cylinder c = start;
  std::vector<int> inliers;
  if (!rebuilt) {
    for (int pass = 0; pass < 3; ++pass) {
      inliers = Inliers(c, kept, threshold);
      c = RefineCylinder(c, kept, inliers);
    }
  }
  inliers = Inliers(c, kept, threshold);
  if (inliers.size() < 8 || c.radius < options.min_radius_m || c.radius > options.max_radius_m ||
      c.axis.z() < std::cos(options.max_tilt_rad)) {
    return std::nullopt;
  }
  TrunkFit fit;
  // Axis point at the base height.
  const double t_base = (base_height - c.point.z()) / c.axis.z();
  fit.cylinder = c;
  fit.base = c.point + t_base * c.axis;
  fit.inliers = static_cast<int>(inliers.size());
  fit.inlier_share = static_cast<double>(inliers.size()) / kept.size();
  double sum2 = 0.0, top = 0.0;
  for (const int i : inliers) {
    const double e = c.AxisDistance(kept[i]) - c.radius;
    sum2 += e * e;
    top = std::max(top, c.AxisCoordinate(kept[i]) - t_base);
  }
  fit.rms_m = std::sqrt(sum2 / inliers.size());
  fit.length_m = top;
  fit.found = true;
  fit.slices = FitSlices(c, fit.base, top, kept, threshold, options);
  if (rebuilt) {
    std::vector<double> fitted;
    for (const TrunkSlice& slice : fit.slices) {
      if (slice.radius_m > 0) fitted.push_back(slice.radius_m);
    }
    if (!fitted.empty()) c.radius = fit.cylinder.radius = UpperMedian(fitted);
    fit.slices = FitSlices(c, fit.base, top, kept, threshold, options);
  }
  std::vector<double> radii;
  for (const TrunkSlice& slice : fit.slices) {
    if (slice.agrees) radii.push_back(slice.radius_m);
  }
  fit.slice_radius_m = radii.empty() ? c.radius : UpperMedian(radii);
  fit.slices_agree = radii.size() == fit.slices.size();
  return fit;
}

// Refines the MSAC cylinder and checks it slice by slice, with two corrections, each at most
// once: when the slice circles agree with each other but not with the cylinder (on a noisy thin
// trunk a wider tilted cylinder can cut through more of the blurred ring than the true one), the
// cylinder is rebuilt from the slice circles; when a slice above the lowest disagrees (a fork, a
// low branch), the fit is shortened to the stretch below it.
TrunkFit RefineAndCheck(std::span<const Eigen::Vector3d> points, Cylinder best, double base_height,
                        double threshold, const TrunkFitOptions& options) {
  TrunkFit fit;
  std::vector<char> use(points.size(), 1);
  bool rebuilt = false, shortened = false;
  for (int round = 0; round < 3; ++round) {
    std::vector<Eigen::Vector3d> kept;
    for (size_t i = 0; i < points.size(); ++i) {
      if (use[i]) kept.push_back(points[i]);
    }
    std::optional<TrunkFit> measured =
        MeasureCylinder(best, rebuilt, kept, base_height, threshold, options);
    if (!measured) {
      fit.note = "the refined cylinder left the tilt and radius limits";
      fit.found = false;
      return fit;
    }
    measured->note = std::move(fit.note);
    fit = std::move(*measured);
    if (fit.slices_agree) break;

    if (!rebuilt) {
      Cylinder consensus;
      if (SliceConsensus(fit.slices, fit.cylinder, threshold, options, &consensus)) {
        fit.note = fmt::format(
            "the MSAC cylinder (radius {:.4f} m) disagreed with the slice circles; rebuilt from "
            "them",
            fit.cylinder.radius);
        best = consensus;
        rebuilt = true;
        continue;
      }
    }
    if (shortened) break;
    int first_bad = 0;
    while (fit.slices[first_bad].agrees) ++first_bad;
    if (first_bad == 0) {
      if (fit.note.empty()) {
        fit.note = "the lowest slice disagrees with the cylinder (root flare or a low fork)";
      }
      break;
    }
    // Keep the stretch below the first disagreeing slice and fit again.
    const double keep_to = fit.slices[first_bad].from_m;
    fit.note += fmt::format("{}shortened to the lowest {:.2f} m, where the slices agree",
                            fit.note.empty() ? "" : "; ", keep_to);
    const double t_base = (base_height - fit.cylinder.point.z()) / fit.cylinder.axis.z();
    for (size_t i = 0; i < points.size(); ++i) {
      use[i] = fit.cylinder.AxisCoordinate(points[i]) - t_base <= keep_to;
    }
    best = fit.cylinder;
    shortened = true;
  }
  return fit;
}

}  // namespace

double Cylinder::AxisDistance(const Eigen::Vector3d& p) const {
  return (p - point).cross(axis).norm();
}

bool FitCircle(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& origin,
               const Eigen::Vector3d& axis, Eigen::Vector3d* centre, double* radius) {
  if (points.size() < 3) return false;
  Eigen::Vector3d e1, e2;
  PlaneBasis(axis, &e1, &e2);
  const std::vector<Eigen::Vector2d> q = InPlane(points, origin, e1, e2);
  // Algebraic (Kasa) fit: x^2 + y^2 + D x + E y + F = 0.
  Eigen::MatrixXd a(q.size(), 3);
  Eigen::VectorXd b(q.size());
  for (size_t i = 0; i < q.size(); ++i) {
    a.row(i) << q[i].x(), q[i].y(), 1.0;
    b[i] = -q[i].squaredNorm();
  }
  const Eigen::Vector3d def = a.colPivHouseholderQr().solve(b);
  Eigen::Vector2d c(-def[0] / 2, -def[1] / 2);
  double r2 = c.squaredNorm() - def[2];
  if (!(r2 > 0) || !c.allFinite()) return false;
  double r = std::sqrt(r2);
  // Geometric refinement (the algebraic fit shrinks circles seen on a partial arc).
  for (int iteration = 0; iteration < 20; ++iteration) {
    Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
    Eigen::Vector3d jtr = Eigen::Vector3d::Zero();
    for (const Eigen::Vector2d& p : q) {
      const Eigen::Vector2d d = p - c;
      const double dist = d.norm();
      if (dist < 1e-12) continue;
      const Eigen::Vector3d j(-d.x() / dist, -d.y() / dist, -1.0);
      jtj += j * j.transpose();
      jtr += j * (dist - r);
    }
    const Eigen::Vector3d step = jtj.ldlt().solve(-jtr);
    if (!step.allFinite()) break;
    c += step.head<2>();
    r += step[2];
    if (step.norm() < 1e-9) break;
  }
  if (!(r > 0) || !std::isfinite(r)) return false;
  *centre = origin + c.x() * e1 + c.y() * e2;
  *radius = r;
  return true;
}

bool FitCircleRobust(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& origin,
                     const Eigen::Vector3d& axis, double min_band_m, Eigen::Vector3d* centre,
                     double* radius) {
  if (points.size() < 3) return false;
  Eigen::Vector3d e1, e2;
  PlaneBasis(axis, &e1, &e2);
  const std::vector<Eigen::Vector2d> q = InPlane(points, origin, e1, e2);
  // MSAC over circles through three points (a fixed seed: the same slab, the same circle), the
  // band `min_band_m` wide ...
  std::mt19937_64 rng(q.size());
  std::uniform_int_distribution<size_t> pick(0, q.size() - 1);
  const double band2 = min_band_m * min_band_m;
  double best_cost = std::numeric_limits<double>::infinity();
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  double r = 0.0;
  for (int it = 0; it < 150; ++it) {
    const Eigen::Vector2d a = q[pick(rng)], b = q[pick(rng)], d = q[pick(rng)];
    // Circumcentre: equidistant from a, b and d.
    Eigen::Matrix2d m;
    m << (b - a).transpose(), (d - a).transpose();
    if (std::abs(m.determinant()) < 1e-12) continue;
    const Eigen::Vector2d rhs(0.5 * (b.squaredNorm() - a.squaredNorm()),
                              0.5 * (d.squaredNorm() - a.squaredNorm()));
    const Eigen::Vector2d h = m.inverse() * rhs;
    const double hr = (a - h).norm();
    if (!std::isfinite(hr) || hr <= 0) continue;
    double cost = 0.0;
    for (const Eigen::Vector2d& p : q) {
      const double e = (p - h).norm() - hr;
      cost += std::min(e * e, band2);
    }
    if (cost < best_cost) {
      best_cost = cost;
      c = h;
      r = hr;
    }
  }
  if (!std::isfinite(best_cost)) return false;
  // ... then a least-squares circle on the points within a band that follows the spread of the
  // residuals (a scaled median absolute deviation, never narrower than `min_band_m`), a few times.
  std::vector<Eigen::Vector3d> band;
  for (int round = 0; round < 4; ++round) {
    std::vector<double> residuals(q.size());
    for (size_t i = 0; i < q.size(); ++i) residuals[i] = std::abs((q[i] - c).norm() - r);
    const double width = std::max(2.5 * 1.4826 * UpperMedian(residuals), min_band_m);
    band.clear();
    for (size_t i = 0; i < q.size(); ++i) {
      if (residuals[i] <= width) band.push_back(points[i]);
    }
    Eigen::Vector3d next;
    double next_r = 0.0;
    if (!FitCircle(band, origin, axis, &next, &next_r)) break;
    const Eigen::Vector3d d = next - origin;
    c = {d.dot(e1), d.dot(e2)};
    r = next_r;
  }
  if (!(r > 0) || !std::isfinite(r)) return false;
  *centre = origin + c.x() * e1 + c.y() * e2;
  *radius = r;
  return true;
}

void TrunkFitOptions::Validate() const {
  CheckAtLeast("iterations", iterations, 1);
  CheckInRange("max_tilt_rad", max_tilt_rad, 0.0, M_PI / 2);
  CheckPositive("min_radius_m", min_radius_m);
  CheckOrdered("min_radius_m", min_radius_m, "max_radius_m", max_radius_m);
  CheckAtLeast("normal_neighbours", normal_neighbours, 3);
  CheckAtLeast("slices", slices, 1);
  CheckNonNegative("slice_radius_tolerance", slice_radius_tolerance);
  CheckNonNegative("slice_centre_tolerance", slice_centre_tolerance);
}

TrunkFit FitTrunkCylinder(std::span<const Eigen::Vector3d> points, double base_height,
                          double inlier_threshold_m, const TrunkFitOptions& options,
                          uint64_t seed) {
  options.Validate();
  CheckPositive("inlier_threshold_m", inlier_threshold_m);
  TrunkFit fit;
  if (points.size() < 10) {
    fit.note =
        fmt::format("{} points around the trunk base: too few for a cylinder", points.size());
    return fit;
  }
  const std::optional<Cylinder> hypothesis =
      MsacCylinder(points, inlier_threshold_m, options, seed);
  if (!hypothesis) {
    fit.note = "no cylinder hypothesis within the tilt and radius limits";
    return fit;
  }
  return RefineAndCheck(points, *hypothesis, base_height, inlier_threshold_m, options);
}

}  // namespace simtree::reconstruction
