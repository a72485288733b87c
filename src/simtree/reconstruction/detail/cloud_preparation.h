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
  double scale = 1.0;  // coordinates are multiplied by this first (0.001 reads millimetres)
  double duplicate_tolerance_m = 1e-6;  // metres (after scaling) within which a point repeats one
  // Metres: a taller cloud is refused as not in metres (the tallest trees are ~115 m; a tree
  // scanned by one RGB-D camera is 1-20 m).
  double max_height_m = 60.0;
  double min_height_m = 0.2;         // metres: a standing tree is at least this tall...
  double min_height_to_width = 0.2;  // ... and at least this share of its width tall
  double extent_trim = 0.002;        // share of points ignored at each end of an extent (strays)

  // Throws OptionError naming the first field out of range.
  void Validate() const;
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
// with no vertical structure; OptionError for invalid options.
PreparedCloud PrepareCloud(std::span<const Eigen::Vector3d> points, const std::string& source,
                           const CloudPreparationOptions& options = {});

// Trimmed extent of `points` along x, y and z: the range between the `trim` and 1 - `trim`
// quantiles of each coordinate.
Eigen::Vector3d TrimmedExtent(std::span<const Eigen::Vector3d> points, double trim);

}  // namespace simtree::reconstruction
