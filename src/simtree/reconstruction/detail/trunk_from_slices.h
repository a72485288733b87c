#pragma once
// The trunk measured slice by slice, and the check that decides whether the MSAC cylinder is
// trusted. MSAC picks the cylinder that holds the most points within its band; on a tall laser
// scan with a root flare, a low fork or a short stretch it can settle on a few points of a huge
// cylinder (a 3.5 m radius from 11 points on a 9 cm trunk). Circles fitted across the trunk one
// slab at a time, each with its own centre, measure what the points say directly: the axis
// follows their centres (slabs cut again across that axis, so a leaning trunk is cut straight),
// the radius is their median. The MSAC cylinder is kept only where these slices vouch for it.

#include <span>
#include <string>

#include <Eigen/Core>

#include "simtree/reconstruction/detail/trunk_cylinder.h"

namespace simtree::reconstruction {

struct SliceTrunkOptions {
  int slices = 6;               // slabs across the stretch
  int min_points = 8;           // points a slab's circle needs
  double min_arc_rad = 2.0;     // radians of the circle its points must cover (~115 degrees)
  double max_residual = 0.35;   // RMS distance from the circle, in radii (plus the band)
  double min_ring_share = 0.5;  // share of the slab's points within the band of the circle
  double agree_share = 0.2;     // slices within this share of the median radius agree...
  int min_agreeing = 3;         // ... and at least this many must
  double max_tilt_rad = 0.6;    // radians of the axis from vertical
  // The MSAC cylinder is trusted when it has this many inliers, covers this share of the
  // stretch and its radius is within `trust_radius_share` of the slices' (when they measured).
  int trust_min_inliers = 20;
  double trust_min_length_share = 0.25;
  double trust_radius_share = 0.3;

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

// The trunk from slabs across the lowest `length_m` above `base_height` of `points` (the scan
// around the trunk base; stray wood is tolerated by the robust circles and the median). `band_m`
// is the noise band of the circle fits. Not found when fewer than min_agreeing slices agree.
TrunkFit FitTrunkFromSlices(std::span<const Eigen::Vector3d> points, double base_height,
                            double length_m, double band_m, const SliceTrunkOptions& options = {});

// Whether `msac` may be used: found, with enough inliers over enough of `stretch_m`, at least one
// of its own slices agreeing with it, and (when `slices` was found) a radius the slices agree
// with. `why` says why not.
bool TrustTrunkCylinder(const TrunkFit& msac, const TrunkFit& slices, double stretch_m,
                        const SliceTrunkOptions& options, std::string* why = nullptr);

}  // namespace simtree::reconstruction
