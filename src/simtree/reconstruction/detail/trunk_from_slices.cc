#include "simtree/reconstruction/detail/trunk_from_slices.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "simtree/core/option_checks.h"
#include "simtree/core/statistics.h"
#include "simtree/core/units.h"
#include "simtree/reconstruction/detail/local_geometry.h"

namespace simtree::reconstruction {
namespace {

// Widest angular share of the circle the points cover, and their RMS distance from it.
void ArcAndResidual(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& centre,
                    double radius, const Eigen::Vector3d& axis, double band, double* arc,
                    double* residual, double* ring_share) {
  Eigen::Vector3d e1, e2;
  PlaneBasis(axis, &e1, &e2);
  std::vector<double> angles;
  double sum2 = 0.0;
  int near = 0, on_ring = 0;
  for (const Eigen::Vector3d& p : points) {
    Eigen::Vector3d d = p - centre;
    d -= d.dot(axis) * axis;
    const double e = d.norm() - radius;
    on_ring += std::abs(e) <= band;
    if (std::abs(e) > 2.0 * band + 0.5 * radius) continue;  // stray wood in the slab
    sum2 += e * e;
    ++near;
    angles.push_back(std::atan2(d.dot(e2), d.dot(e1)));
  }
  *arc = 0.0;
  *residual = std::numeric_limits<double>::infinity();
  *ring_share = points.empty() ? 0.0 : static_cast<double>(on_ring) / points.size();
  if (near < 3) return;
  std::sort(angles.begin(), angles.end());
  double widest_gap = kTwoPi - (angles.back() - angles.front());
  for (size_t k = 1; k < angles.size(); ++k) {
    widest_gap = std::max(widest_gap, angles[k] - angles[k - 1]);
  }
  *arc = kTwoPi - widest_gap;
  *residual = std::sqrt(sum2 / near);
}

// Circles across `axis` in slabs along it from `base` up to `length`.
std::vector<TrunkSlice> CutSlices(std::span<const Eigen::Vector3d> points,
                                  const Eigen::Vector3d& base, const Eigen::Vector3d& axis,
                                  double length, double band, const SliceTrunkOptions& options) {
  const int n = options.slices;
  std::vector<std::vector<Eigen::Vector3d>> slab(n);
  for (const Eigen::Vector3d& p : points) {
    const double t = (p - base).dot(axis);
    if (t < 0 || t > length) continue;
    slab[std::min(n - 1, static_cast<int>(t / length * n))].push_back(p);
  }
  std::vector<TrunkSlice> out(n);
  for (int s = 0; s < n; ++s) {
    TrunkSlice& slice = out[s];
    slice.from_m = length * s / n;
    slice.to_m = length * (s + 1) / n;
    slice.points = static_cast<int>(slab[s].size());
    const Eigen::Vector3d origin = base + axis * 0.5 * (slice.from_m + slice.to_m);
    Eigen::Vector3d centre;
    double radius = 0.0;
    if (slice.points < options.min_points ||
        !FitCircleRobust(slab[s], origin, axis, band, &centre, &radius)) {
      continue;
    }
    double arc = 0.0, residual = 0.0, ring_share = 0.0;
    ArcAndResidual(slab[s], centre, radius, axis, band, &arc, &residual, &ring_share);
    if (arc < options.min_arc_rad || residual > options.max_residual * radius + band ||
        ring_share < options.min_ring_share) {
      continue;
    }
    slice.centre = centre;
    slice.radius_m = radius;
  }
  return out;
}

// Marks the slices within agree_share of their median radius; returns that median (0 when
// fewer than min_agreeing agree).
double MarkAgreement(std::vector<TrunkSlice>& slices, double band,
                     const SliceTrunkOptions& options) {
  std::vector<double> radii;
  for (const TrunkSlice& s : slices) {
    if (s.radius_m > 0) radii.push_back(s.radius_m);
  }
  if (static_cast<int>(radii.size()) < options.min_agreeing) return 0.0;
  // The lower median: a root flare and stray wood widen slices, nothing narrows a trunk.
  std::sort(radii.begin(), radii.end());
  const double median = radii[(radii.size() - 1) / 2];
  int agreeing = 0;
  for (TrunkSlice& s : slices) {
    s.agrees =
        s.radius_m > 0 && std::abs(s.radius_m - median) <= options.agree_share * median + band;
    agreeing += s.agrees;
  }
  return agreeing >= options.min_agreeing ? median : 0.0;
}

// Least-squares line through the agreeing slices' centres (direction up).
bool AxisThroughCentres(std::span<const TrunkSlice> slices, Eigen::Vector3d* point,
                        Eigen::Vector3d* axis) {
  std::vector<Eigen::Vector3d> centres;
  for (const TrunkSlice& s : slices) {
    if (s.agrees) centres.push_back(s.centre);
  }
  if (centres.size() < 2) return false;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& c : centres) mean += c;
  mean /= centres.size();
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& c : centres) scatter += (c - mean) * (c - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  Eigen::Vector3d a = eig.eigenvectors().col(2);
  if (a.z() < 0) a = -a;
  *point = mean;
  *axis = a;
  return a.allFinite();
}

}  // namespace

void SliceTrunkOptions::Validate() const {
  CheckAtLeast("slices", slices, 3);
  CheckAtLeast("min_points", min_points, 3);
  CheckInRange("min_arc_rad", min_arc_rad, 0.0, 2 * M_PI);
  CheckPositive("max_residual", max_residual);
  CheckShare("min_ring_share", min_ring_share);
  CheckPositive("agree_share", agree_share);
  CheckAtLeast("min_agreeing", min_agreeing, 2);
  CheckInRange("max_tilt_rad", max_tilt_rad, 0.0, M_PI / 2);
  CheckAtLeast("trust_min_inliers", trust_min_inliers, 0);
  CheckShare("trust_min_length_share", trust_min_length_share);
  CheckPositive("trust_radius_share", trust_radius_share);
}

TrunkFit FitTrunkFromSlices(std::span<const Eigen::Vector3d> points, double base_height,
                            double length_m, double band_m, const SliceTrunkOptions& options) {
  options.Validate();
  CheckPositive("length_m", length_m);
  CheckPositive("band_m", band_m);
  TrunkFit fit;
  // First cut: horizontal slabs from the lowest points' centroid.
  Eigen::Vector3d base = Eigen::Vector3d::Zero();
  int low = 0;
  for (const Eigen::Vector3d& p : points) {
    if (p.z() <= base_height + length_m / options.slices) {
      base += p;
      ++low;
    }
  }
  if (low == 0) {
    fit.note = "no points in the lowest slab";
    return fit;
  }
  base /= low;
  base.z() = base_height;
  // Cut horizontally, then across the line through the circles' centres, while that narrows
  // the circles: a cut across a trunk is its narrowest, an oblique one an ellipse (a leaning
  // trunk), and centres scattered by a flare must not tilt a straight one.
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double radius = 0.0;
  for (int round = 0; round < 3; ++round) {
    std::vector<TrunkSlice> slices = CutSlices(points, base, axis, length_m, band_m, options);
    const double r = MarkAgreement(slices, band_m, options);
    Eigen::Vector3d point, next_axis;
    if (r <= 0 || !AxisThroughCentres(slices, &point, &next_axis)) break;
    if (radius > 0 && r >= radius) break;  // the previous cut was narrower
    radius = r;
    fit.slices = std::move(slices);
    // The axis through the centres at the height of their mean; kept vertical when the centres
    // lean beyond the limit.
    if (next_axis.z() < std::cos(options.max_tilt_rad)) next_axis = axis;
    fit.cylinder.point = point;
    fit.cylinder.axis = axis;
    fit.cylinder.radius = radius;
    if (next_axis.dot(axis) > std::cos(DegToRad(1))) break;
    axis = next_axis;
    base = point + ((base_height - point.z()) / axis.z()) * axis;
  }
  if (radius <= 0) {
    fit.note = "fewer than " + std::to_string(options.min_agreeing) +
               " slices across the trunk agree on a circle";
    return fit;
  }
  base = fit.cylinder.point +
         ((base_height - fit.cylinder.point.z()) / fit.cylinder.axis.z()) * fit.cylinder.axis;
  fit.found = true;
  fit.base = base;
  fit.length_m = length_m;
  fit.slice_radius_m = radius;
  int agreeing = 0, inliers = 0;
  double sum2 = 0.0;
  for (const TrunkSlice& s : fit.slices) agreeing += s.agrees;
  for (const Eigen::Vector3d& p : points) {
    const double along = fit.cylinder.AxisCoordinate(p) - fit.cylinder.AxisCoordinate(base);
    const double e = fit.cylinder.AxisDistance(p) - radius;
    if (along >= 0 && along <= length_m && std::abs(e) <= band_m) {
      ++inliers;
      sum2 += e * e;
    }
  }
  fit.inliers = inliers;
  fit.inlier_share = points.empty() ? 0.0 : static_cast<double>(inliers) / points.size();
  fit.rms_m = inliers ? std::sqrt(sum2 / inliers) : 0.0;
  fit.slices_agree = agreeing == static_cast<int>(fit.slices.size());
  fit.note =
      fmt::format("measured on {} of {} slices across the trunk", agreeing, fit.slices.size());
  return fit;
}

bool TrustTrunkCylinder(const TrunkFit& msac, const TrunkFit& slices, double stretch_m,
                        const SliceTrunkOptions& options, std::string* why) {
  std::string reason;
  if (!msac.found) {
    reason = "no MSAC cylinder";
  } else if (msac.inliers < options.trust_min_inliers) {
    reason = fmt::format("the MSAC cylinder holds {} points", msac.inliers);
  } else if (std::none_of(msac.slices.begin(), msac.slices.end(),
                          [](const TrunkSlice& s) { return s.agrees; })) {
    reason = "no slice agrees with the MSAC cylinder";
  } else if (msac.length_m < options.trust_min_length_share * stretch_m) {
    reason = fmt::format("the MSAC cylinder covers {:.2f} of {:.2f} m", msac.length_m, stretch_m);
  } else if (slices.found && std::abs(msac.slice_radius_m - slices.slice_radius_m) >
                                 options.trust_radius_share * slices.slice_radius_m) {
    reason = fmt::format("the MSAC radius {:.3f} m disagrees with the slices' {:.3f} m",
                         msac.slice_radius_m, slices.slice_radius_m);
  }
  if (why) *why = reason;
  return reason.empty();
}

}  // namespace simtree::reconstruction
