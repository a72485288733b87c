#pragma once
// The two lengths every reconstruction parameter is scaled from: how far apart neighbouring scan
// points are and how rough the scanned surfaces are (sensor noise, plus bark and curvature).
// Measured at a seeded sample of points; a cloud larger than `max_indexed_points` is itself
// subsampled first and its spacing scaled back (on a surface, spacing goes with 1/sqrt(density)).

#include <cstdint>
#include <span>

#include <Eigen/Core>

namespace simtree::reconstruction {

struct CloudScaleOptions {
  int samples = 3000;                  // points measured (all when the cloud is smaller)
  size_t max_indexed_points = 100000;  // a larger cloud is subsampled to this many first
  int noise_neighbours = 12;           // points in the neighbourhood of a roughness plane fit
  uint64_t seed = 1;                   // of the sample

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

struct CloudScale {
  // Median distance from a point to its nearest neighbour (metres).
  double spacing_m = 0.0;
  // Median distance to the 6th nearest neighbour: the size of a neighbourhood. In a cloud merged
  // from overlapping views the nearest neighbour often comes from another view and is much closer
  // than the sampling of any one view; this is not fooled by that.
  double neighbourhood_m = 0.0;
  // Median RMS distance of a point's neighbourhood from its best-fit plane (metres): the noise on
  // flat-enough surfaces, an upper bound where branches are thin.
  double roughness_m = 0.0;
};

// Returns zeros for fewer than three points.
CloudScale MeasureCloudScale(std::span<const Eigen::Vector3d> points,
                             const CloudScaleOptions& options = {});

}  // namespace simtree::reconstruction
