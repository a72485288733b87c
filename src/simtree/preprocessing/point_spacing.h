#pragma once
// The typical distance between neighbouring points of a cloud: every voxel size, radius and
// threshold of preprocessing and registration is a multiple of it (or of the measured noise), so
// the same defaults work for a sensor at 1 m and at 3 m.

#include <cstdint>

#include <open3d/geometry/PointCloud.h>

namespace simtree::preprocessing {

struct SpacingOptions {
  size_t max_samples = 4000;  // points whose nearest neighbour is measured (a seeded sample), > 0
  // Neighbours searched per point (the point itself included), >= 2: the nearest one that is
  // not an exact duplicate counts.
  int neighbours = 4;
  uint64_t seed = 1;  // of the sample

  // Throws InputError naming the field of a nonsense value.
  void Validate() const;
};

// Median distance from a point to its nearest neighbour; 0 for clouds of fewer than two points.
double MedianPointSpacing(const open3d::geometry::PointCloud& cloud,
                          const SpacingOptions& options = {});

}  // namespace simtree::preprocessing
