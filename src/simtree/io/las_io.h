#pragma once
// LAS point clouds (ASPRS LAS 1.0-1.4, uncompressed), what laser scanners and photogrammetry
// tools export: point formats 0-3 and 6-8, coordinates scaled and offset as the header says,
// colour (formats 2, 3, 7, 8) kept. LAZ (compressed LAS) is refused with a message saying how to
// decompress it. ReadPointCloud (io/point_cloud_io.h) calls this for .las files.

#include <cstdint>
#include <filesystem>

#include <open3d/geometry/PointCloud.h>

namespace simtree {

struct LasReadReport {
  int version_major = 0;
  int version_minor = 0;
  int point_format = 0;
  uint64_t points = 0;
  bool has_color = false;
};

// Throws InputError naming the file and header field for a file that is not LAS, is compressed
// (LAZ), has a point format outside 0-3 and 6-8, a record shorter than its format, or is shorter
// than its header says.
open3d::geometry::PointCloud ReadLas(const std::filesystem::path& path,
                                     LasReadReport* report = nullptr);

}  // namespace simtree
