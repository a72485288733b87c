#pragma once
// The ground under a scanned tree, when the scan kept it: a near-horizontal plane through the
// lowest points (seeded RANSAC) that is much wider than the trunk standing on it. Segmented tree
// scans have no ground; then nothing is found and the tree's base is its lowest wood.

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

namespace simtree {

struct GroundOptions {
  double tolerance_m = 0.02;      // plane inliers
  double max_tilt_rad = 0.26;     // from horizontal (~15 degrees)
  double search_share = 0.15;     // of the tree's height, from the bottom, searched for ground
  double min_width_m = 0.5;       // the ground patch must be at least this wide...
  double width_over_trunk = 2.5;  // ... and this many times the width of what stands on it
  int min_points = 30;
  int iterations = 300;
  uint64_t seed = 1;
};

struct GroundPlane {
  bool found = false;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // upwards
  double offset = 0.0;                                // plane: normal . p + offset = 0
  std::vector<char> is_ground;  // per point: on the plane (within tolerance) or below it
  size_t ground_points = 0;

  double HeightAbove(const Eigen::Vector3d& p) const { return normal.dot(p) + offset; }
  // z of the plane at (x, y).
  double HeightAt(double x, double y) const;
};

GroundPlane FindGroundPlane(std::span<const Eigen::Vector3d> points,
                            const GroundOptions& options = {});

}  // namespace simtree
