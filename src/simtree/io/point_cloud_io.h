#pragma once
// Point cloud files. Text clouds (.xyz, .txt, .pts: "x y z" per line, further columns ignored) are
// parsed here, strictly, with line numbers in errors; .ply and .pcd go through Open3D; .las through
// io/las_io.h (.laz is refused with advice). Points with NaN or infinite coordinates are dropped
// with a warning that says how many and where the first was.

#include <filesystem>
#include <string>

#include <open3d/geometry/PointCloud.h>

namespace simtree {

struct PointCloudReadReport {
  size_t points = 0;
  size_t dropped_non_finite = 0;
  int first_non_finite_line = 0;  // text files only, 0 when none
};

// True when `path`'s extension is one ReadPointCloud reads (any case).
bool IsPointCloudFile(const std::filesystem::path& path);

// Throws InputError for an unreadable, empty or all-NaN file.
open3d::geometry::PointCloud ReadPointCloud(const std::filesystem::path& path,
                                            PointCloudReadReport* report = nullptr);

// Writes by extension (.ply binary, .pcd, .xyz), atomically. Throws IoError on failure.
void WritePointCloud(const open3d::geometry::PointCloud& cloud, const std::filesystem::path& path);

}  // namespace simtree
