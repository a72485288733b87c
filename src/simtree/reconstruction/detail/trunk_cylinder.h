#pragma once
// The trunk as the paper measures it: a cylinder fitted to the lowest part of the trunk by
// M-estimator sample consensus (MSAC: random two-point hypotheses from points and their normals,
// scored by a truncated squared distance so outliers cost a constant), refined by least squares
// on its inliers, then checked slice by slice: a circle fitted to each slice along the axis must
// agree with the cylinder (a fork, a low branch or a leaning base shows up as a disagreeing slice
// and the fit is shortened to the slices that agree). The slice circles are fitted robustly, each
// with its own centre; when they agree with each other but not with the cylinder (a thin trunk
// under noise as wide as its radius, where a wider tilted cylinder cuts through more of the blurred
// ring), the cylinder is rebuilt from them: axis through their centres, radius their median.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace simtree::reconstruction {

struct Cylinder {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // on the axis
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit
  double radius = 0.0;
  // Distance of `p` from the axis line.
  double AxisDistance(const Eigen::Vector3d& p) const;
  // Coordinate of `p` along the axis, from `point`.
  double AxisCoordinate(const Eigen::Vector3d& p) const { return (p - point).dot(axis); }
};

struct TrunkFitOptions {
  int iterations = 400;                  // MSAC hypotheses
  double max_tilt_rad = 0.6;             // radians of the axis from vertical (~35 degrees)
  double min_radius_m = 0.004;           // metres, smallest cylinder accepted
  double max_radius_m = 1.5;             // metres, largest cylinder accepted
  int normal_neighbours = 12;            // points in each normal's plane fit
  int slices = 5;                        // slices along the axis checked against the cylinder
  double slice_radius_tolerance = 0.12;  // a slice agrees within this share of the radius...
  double slice_centre_tolerance = 0.25;  // ... and its centre within this many radii of the axis

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

struct TrunkSlice {
  double from_m = 0.0, to_m = 0.0;  // along the axis, from the base
  int points = 0;
  double radius_m = 0.0;  // circle fitted to the slice; 0 when too few points
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // of that circle
  double centre_offset_m = 0.0;                      // of that circle from the cylinder axis
  bool agrees = false;
};

struct TrunkFit {
  bool found = false;
  Cylinder cylinder;
  Eigen::Vector3d base = Eigen::Vector3d::Zero();  // axis point at the base height
  double length_m = 0.0;                           // fitted stretch, along the axis from `base`
  int inliers = 0;
  double inlier_share = 0.0;
  double rms_m = 0.0;  // RMS distance of the inliers from the surface
  std::vector<TrunkSlice> slices;
  bool slices_agree = false;
  // Median radius of the slice circles (each with its own centre, so a trunk that bends a little
  // does not widen it as it widens the straight cylinder); the cylinder radius when no slice fits.
  double slice_radius_m = 0.0;
  std::string note;  // why the fit failed or was shortened
};

// Fits the trunk to `points` (the scan around the lower trunk; other wood is tolerated as
// outliers). `base_height` is the z of the tree's base; `base` is the axis point at that z.
// `inlier_threshold_m` is the MSAC truncation (points this far from the surface count; also the
// slack of the slice checks); `seed` drives the hypotheses.
TrunkFit FitTrunkCylinder(std::span<const Eigen::Vector3d> points, double base_height,
                          double inlier_threshold_m, const TrunkFitOptions& options = {},
                          uint64_t seed = 1);

// Circle through points projected on the plane normal to `axis` (algebraic fit, then a few
// geometric Gauss-Newton steps): centre (3D, in the plane through `origin`) and radius. False
// with fewer than 3 points or a degenerate set.
bool FitCircle(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& origin,
               const Eigen::Vector3d& axis, Eigen::Vector3d* centre, double* radius);

// FitCircle made robust to stray points (a low branch, a prop, noise): started from the median
// point and distance, refitted a few times on the points within a band that follows the spread of
// the residuals, never narrower than `min_band_m`.
bool FitCircleRobust(std::span<const Eigen::Vector3d> points, const Eigen::Vector3d& origin,
                     const Eigen::Vector3d& axis, double min_band_m, Eigen::Vector3d* centre,
                     double* radius);

}  // namespace simtree::reconstruction
