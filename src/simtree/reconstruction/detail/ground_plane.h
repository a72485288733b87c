#pragma once
// The ground under a scanned tree, when the scan kept it: a near-horizontal plane through the
// lowest points (seeded RANSAC) that is wide and mostly open (a trunk, boxes or posts stand on a
// small part of it). Segmented tree scans have no ground; then nothing is found and the tree's
// base is its lowest wood.

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

namespace simtree::reconstruction {

struct GroundOptions {
  double tolerance_m = 0.02;       // metres from the plane that count as on it
  double max_tilt_rad = 0.26;      // radians of the plane from horizontal (~15 degrees)
  double search_share = 0.15;      // share of the cloud's height, from the bottom, searched
  double min_width_m = 0.5;        // metres: the ground patch is at least this wide...
  double max_covered_share = 0.5;  // ... and at most this share of it has something standing
                                   // right above it (a trunk's base ring has wood above all)
  int min_points = 30;             // points on the plane, at least
  int iterations = 300;            // RANSAC hypotheses
  int max_scored_points = 20000;   // hypotheses are scored on an even subset of the low points

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

struct GroundPlane {
  bool found = false;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // upwards
  double offset = 0.0;                                // plane: normal . p + offset = 0
  std::vector<char> is_ground;  // per point: on the plane (within the clearance) or below it
  double clearance_m = 0.0;     // the tolerance, or 4 robust sigmas of a noisier ground
  size_t ground_points = 0;
  // The checks' measurements (also when rejected): trimmed widths of the plane's inliers and of
  // what stands just above it.
  double plane_width_m = 0.0;
  double standing_width_m = 0.0;
  double covered_share = 0.0;  // of the plane's points with something standing right above

  double HeightAbove(const Eigen::Vector3d& p) const { return normal.dot(p) + offset; }
  // z of the plane at (x, y).
  double HeightAt(double x, double y) const;
};

// `seed` drives the RANSAC hypotheses: the same points and seed give the same plane.
GroundPlane FindGroundPlane(std::span<const Eigen::Vector3d> points,
                            const GroundOptions& options = {}, uint64_t seed = 1);

}  // namespace simtree::reconstruction
