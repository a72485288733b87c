#include "simtree/io/point_cloud_io.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <open3d/io/PointCloudIO.h>
#include <spdlog/spdlog.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/io/detail/cloud_header_check.h"
#include "simtree/io/las_io.h"

namespace fs = std::filesystem;

namespace simtree {
namespace {

std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool IsText(const std::string& ext) { return ext == ".xyz" || ext == ".txt" || ext == ".pts"; }

// Parses "x y z ..." lines. Accepts commas or whitespace between numbers; skips blank lines and
// lines starting with '#' or '//'.
open3d::geometry::PointCloud ReadTextCloud(const fs::path& path, PointCloudReadReport& report) {
  const std::string text = ReadFile(path);
  open3d::geometry::PointCloud cloud;
  cloud.points_.reserve(text.size() / 24);
  const char* p = text.data();
  const char* end = p + text.size();
  int line = 0;
  while (p < end) {
    ++line;
    const char* eol = std::find(p, end, '\n');
    const char* q = p;
    auto skip = [&] {
      while (q < eol && (*q == ' ' || *q == '\t' || *q == ',' || *q == '\r')) ++q;
    };
    skip();
    if (q == eol || *q == '#' || (eol - q >= 2 && q[0] == '/' && q[1] == '/')) {
      p = eol + 1;
      continue;
    }
    double xyz[3];
    for (int k = 0; k < 3; ++k) {
      skip();
      auto [ptr, ec] = std::from_chars(q, eol, xyz[k]);
      if (ec != std::errc() || ptr == q) {
        // from_chars does not read "nan"/"inf" in every spelling; treat those as non-finite.
        const std::string word(q, std::find_if(q, eol, [](char c) {
                                 return c == ' ' || c == '\t' || c == ',' || c == '\r';
                               }));
        const std::string lower = Lower(word);
        if (lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos) {
          xyz[k] = std::nan("");
          q += word.size();
          continue;
        }
        if (report.points == 0 && line == 1 && k == 0) {
          // A header line ("x y z") is tolerated once.
          break;
        }
        throw InputError(path.string(), fmt::format("line {}", line),
                         fmt::format("expected 3 numbers \"x y z\", got \"{}\"",
                                     std::string(p, eol - p > 60 ? p + 60 : eol)));
      }
      q = ptr;
      if (k == 2) {
        if (std::isfinite(xyz[0]) && std::isfinite(xyz[1]) && std::isfinite(xyz[2])) {
          cloud.points_.emplace_back(xyz[0], xyz[1], xyz[2]);
          // A text file has no count up front: stop at the limit, before memory runs out.
          if (++report.points > static_cast<size_t>(cloud_detail::kMaxCloudPoints)) {
            cloud_detail::CheckPointCount(path.string(), fmt::format("line {}", line),
                                          static_cast<int64_t>(report.points));
          }
        } else {
          if (report.dropped_non_finite == 0) report.first_non_finite_line = line;
          ++report.dropped_non_finite;
        }
      }
    }
    p = eol + 1;
  }
  return cloud;
}

}  // namespace

bool IsPointCloudFile(const fs::path& path) {
  const std::string ext = Lower(path.extension().string());
  return IsText(ext) || ext == ".ply" || ext == ".pcd" || ext == ".las" || ext == ".laz";
}

open3d::geometry::PointCloud ReadPointCloud(const fs::path& path, PointCloudReadReport* report) {
  PointCloudReadReport local;
  PointCloudReadReport& r = report ? *report : local;
  r = {};
  if (!fs::exists(path)) throw IoError(fmt::format("{}: no such file", path.string()));
  if (fs::is_directory(path)) {
    throw InputError(path.string(), "", "expected a point cloud file, got a folder");
  }
  const std::string ext = Lower(path.extension().string());
  open3d::geometry::PointCloud cloud;
  if (IsText(ext)) {
    cloud = ReadTextCloud(path, r);
  } else if (ext == ".ply" || ext == ".pcd") {
    if (fs::file_size(path) == 0) throw InputError(path.string(), "", "the file is empty");
    // Open3D allocates what the header claims before reading: refuse what cannot be.
    if (ext == ".ply") {
      cloud_detail::CheckPlyHeader(path);
    } else {
      cloud_detail::CheckPcdHeader(path);
    }
    open3d::io::ReadPointCloudOption option;
    option.remove_nan_points = false;
    option.remove_infinite_points = false;
    if (!open3d::io::ReadPointCloud(path.string(), cloud, option)) {
      throw InputError(path.string(), "",
                       "Open3D could not read this file (truncated or not a "
                       "point cloud?)");
    }
    auto& pts = cloud.points_;
    const size_t before = pts.size();
    // Drop non-finite points together with their normals and colours.
    std::vector<size_t> keep;
    keep.reserve(before);
    for (size_t i = 0; i < before; ++i) {
      if (pts[i].allFinite()) keep.push_back(i);
    }
    if (keep.size() != before) cloud = *cloud.SelectByIndex(keep);
    r.points = cloud.points_.size();
    r.dropped_non_finite = before - r.points;
  } else if (ext == ".las" || ext == ".laz") {
    cloud = ReadLas(path);
    r.points = cloud.points_.size();
  } else {
    throw InputError(path.string(), "",
                     fmt::format("expected a point cloud ending in .xyz, .txt, .pts, .ply, .pcd or "
                                 ".las, got \"{}\"",
                                 ext));
  }
  if (r.dropped_non_finite > 0) {
    spdlog::warn("{}: dropped {} points with NaN or infinite coordinates{}", path.string(),
                 r.dropped_non_finite,
                 r.first_non_finite_line > 0
                     ? fmt::format(" (first on line {})", r.first_non_finite_line)
                     : "");
  }
  if (cloud.points_.empty()) {
    throw InputError(path.string(), "",
                     r.dropped_non_finite > 0 ? "every point has NaN or infinite coordinates"
                                              : "expected points, the file has none");
  }
  return cloud;
}

void WritePointCloud(const open3d::geometry::PointCloud& cloud, const fs::path& path) {
  AtomicFile file(path, /*binary=*/true);
  open3d::io::WritePointCloudOption option;
  option.write_ascii = open3d::io::WritePointCloudOption::IsAscii::Binary;
  if (!open3d::io::WritePointCloud(file.temporary_path().string(), cloud, option)) {
    throw IoError(fmt::format("{}: could not write the point cloud", path.string()));
  }
  file.Commit();
}

}  // namespace simtree
