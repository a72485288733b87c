#pragma once
// What reconstruction checks about a cloud before it trusts it: finite coordinates, no repeated
// points, metres (a tree scanned in millimetres is 1000 times too tall) and a standing shape (a
// tree is taller than a small fraction of its width). Problems that can be fixed are fixed with a
// warning; the others are InputErrors that say what was expected.

#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace simtree::reconstruction {

struct CloudPreparationOptions {
  // Coordinates are multiplied by this first (0.001 reads a cloud in millimetres).
  double scale = 1.0;
  // Points closer than this to an earlier point are duplicates (metres, after scaling).
  double duplicate_tolerance_m = 1e-6;
  // A cloud taller than this is refused as not being in metres (the tallest trees are ~115 m; a
  // tree scanned by one RGB-D camera is 1-20 m).
  double max_height_m = 60.0;
  // A standing tree: at least this tall, and at least `min_height_to_width` of its width.
  double min_height_m = 0.2;
  double min_height_to_width = 0.2;
  // Share of points ignored at each end when measuring extents (stray outliers).
  double extent_trim = 0.002;
};

struct PreparedCloud {
  std::vector<Eigen::Vector3d> points;  // finite, scaled, without duplicates, in input order
  size_t input_points = 0;
  size_t dropped_non_finite = 0;
  size_t dropped_duplicates = 0;
  Eigen::Vector3d extent = Eigen::Vector3d::Zero();  // trimmed extent along x, y, z (metres)
  std::vector<std::string> warnings;                 // also logged
};

// Throws InputError naming `source` for an empty cloud, one with no finite point, a cloud that
// is not in metres (saying which unit it looks like and the --scale that fixes it) and a cloud
// with no vertical structure.
PreparedCloud PrepareCloud(std::span<const Eigen::Vector3d> points, const std::string& source,
                           const CloudPreparationOptions& options = {});

// Trimmed extent of `points` along x, y and z: the range between the `trim` and 1 - `trim`
// quantiles of each coordinate.
Eigen::Vector3d TrimmedExtent(std::span<const Eigen::Vector3d> points, double trim);

}  // namespace simtree::reconstruction
