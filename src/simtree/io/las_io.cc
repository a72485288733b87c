// LAS reading after the ASPRS LAS specification (1.4 R15): the public header block's fields at
// their fixed offsets, then point records of `point record length` bytes from `offset to point
// data`. Read in blocks, so memory stays at the cloud plus one block.

#include "simtree/io/las_io.h"

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/io/detail/cloud_header_check.h"

namespace simtree {

namespace fs = std::filesystem;

namespace {

static_assert(std::endian::native == std::endian::little, "LAS is little-endian");

template <typename T>
T At(const char* bytes, size_t offset) {
  T value;
  std::memcpy(&value, bytes + offset, sizeof(T));
  return value;
}

// Where a point format keeps its colour (-1: none) and its shortest record.
struct PointLayout {
  int color_offset = -1;
  int min_length = 0;
};

std::optional<PointLayout> LayoutOf(int format) {
  switch (format) {
    case 0:
      return PointLayout{-1, 20};
    case 1:
      return PointLayout{-1, 28};
    case 2:
      return PointLayout{20, 26};
    case 3:
      return PointLayout{28, 34};
    case 6:
      return PointLayout{-1, 30};
    case 7:
      return PointLayout{30, 36};
    case 8:
      return PointLayout{30, 38};
    default:
      return std::nullopt;
  }
}

constexpr const char* kLazAdvice =
    "LAZ (compressed LAS) is not read; decompress it first, e.g. `laszip -i scan.laz -o "
    "scan.las` or `pdal translate scan.laz scan.las`";

struct Header {
  int major = 0, minor = 0;
  uint32_t header_size = 0;
  uint32_t point_offset = 0;
  int format = 0;
  uint32_t record_length = 0;
  uint64_t points = 0;
  double scale[3] = {0, 0, 0};
  double offset[3] = {0, 0, 0};
};

Header ReadHeader(std::ifstream& in, const fs::path& path, uint64_t file_size) {
  const std::string source = path.string();
  std::array<char, 375> b{};
  if (file_size < 227) {
    throw InputError(source, "",
                     fmt::format("expected a LAS header (227 bytes or more), the file "
                                 "has {} bytes",
                                 file_size));
  }
  in.read(b.data(), static_cast<std::streamsize>(std::min<uint64_t>(file_size, b.size())));
  if (std::memcmp(b.data(), "LASF", 4) != 0) {
    throw InputError(source, "file signature", "expected \"LASF\": not a LAS file");
  }
  Header h;
  h.major = static_cast<uint8_t>(b[24]);
  h.minor = static_cast<uint8_t>(b[25]);
  if (h.major != 1 || h.minor > 4) {
    throw InputError(source, "version",
                     fmt::format("expected LAS 1.0-1.4, got {}.{}", h.major, h.minor));
  }
  h.header_size = At<uint16_t>(b.data(), 94);
  h.point_offset = At<uint32_t>(b.data(), 96);
  const int format_byte = static_cast<uint8_t>(b[104]);
  h.record_length = At<uint16_t>(b.data(), 105);
  // LAZ marks its compressed records by setting the top bits of the point format.
  if (format_byte & 0xC0) throw InputError(source, "point data format", kLazAdvice);
  h.format = format_byte;
  const std::optional<PointLayout> layout = LayoutOf(h.format);
  if (!layout) {
    throw InputError(source, "point data format",
                     fmt::format("point format {} is not read (simtree reads formats 0-3 and "
                                 "6-8; 4, 5, 9 and 10 carry waveforms)",
                                 h.format));
  }
  if (h.record_length < static_cast<uint32_t>(layout->min_length)) {
    throw InputError(source, "point data record length",
                     fmt::format("expected at least {} bytes for point format {}, got {}",
                                 layout->min_length, h.format, h.record_length));
  }
  const uint32_t min_header = h.minor >= 4 ? 375 : h.minor == 3 ? 235 : 227;
  if (h.header_size < min_header || h.header_size > file_size) {
    throw InputError(source, "header size",
                     fmt::format("expected at least {} bytes for LAS 1.{} within the file's {}, "
                                 "got {}",
                                 min_header, h.minor, file_size, h.header_size));
  }
  h.points = At<uint32_t>(b.data(), 107);
  // 1.4 counts in 64 bits; a writer that filled only the legacy field (formats 0-5) is read too.
  if (h.minor >= 4 && At<uint64_t>(b.data(), 247) > 0) h.points = At<uint64_t>(b.data(), 247);
  cloud_detail::CheckPointCount(source, "number of point records",
                                static_cast<int64_t>(std::min<uint64_t>(h.points, INT64_MAX)));
  for (int k = 0; k < 3; ++k) {
    h.scale[k] = At<double>(b.data(), 131 + 8 * k);
    h.offset[k] = At<double>(b.data(), 155 + 8 * k);
    if (!std::isfinite(h.scale[k]) || h.scale[k] == 0 || !std::isfinite(h.offset[k])) {
      throw InputError(source, fmt::format("{} scale factor and offset", "xyz"[k]),
                       fmt::format("expected a finite, non-zero scale and a finite offset, got "
                                   "{} and {}",
                                   h.scale[k], h.offset[k]));
    }
  }
  if (h.point_offset < h.header_size) {
    throw InputError(
        source, "offset to point data",
        fmt::format("expected at least the header size {}, got {}", h.header_size, h.point_offset));
  }
  const uint64_t room =
      (file_size - std::min<uint64_t>(file_size, h.point_offset)) / h.record_length;
  if (room < h.points) {
    throw InputError(source, "number of point records",
                     fmt::format("the header says {} points of {} bytes from byte {}, the file "
                                 "holds {} (truncated?)",
                                 h.points, h.record_length, h.point_offset, room));
  }
  return h;
}

}  // namespace

open3d::geometry::PointCloud ReadLas(const fs::path& path, LasReadReport* report) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".laz") throw InputError(path.string(), "", kLazAdvice);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(fmt::format("{}: cannot open", path.string()));
  const Header h = ReadHeader(in, path, fs::file_size(path));
  const int color_offset = LayoutOf(h.format)->color_offset;

  open3d::geometry::PointCloud cloud;
  cloud.points_.reserve(h.points);
  std::vector<std::array<uint16_t, 3>> rgb;
  if (color_offset >= 0) rgb.reserve(h.points);
  in.seekg(h.point_offset);
  constexpr uint64_t kBlock = 65536;
  std::vector<char> block;
  for (uint64_t done = 0; done < h.points;) {
    const uint64_t n = std::min(kBlock, h.points - done);
    block.resize(n * h.record_length);
    if (!in.read(block.data(), static_cast<std::streamsize>(block.size()))) {
      throw InputError(path.string(), fmt::format("point {}", done), "unexpected end of file");
    }
    for (uint64_t i = 0; i < n; ++i) {
      const char* p = block.data() + i * h.record_length;
      cloud.points_.emplace_back(At<int32_t>(p, 0) * h.scale[0] + h.offset[0],
                                 At<int32_t>(p, 4) * h.scale[1] + h.offset[1],
                                 At<int32_t>(p, 8) * h.scale[2] + h.offset[2]);
      if (color_offset >= 0) {
        rgb.push_back({At<uint16_t>(p, color_offset), At<uint16_t>(p, color_offset + 2),
                       At<uint16_t>(p, color_offset + 4)});
      }
    }
    done += n;
  }
  if (!rgb.empty()) {
    // The specification asks for 16-bit colour, but many writers store 8-bit values as they are.
    uint16_t max = 0;
    for (const auto& c : rgb) max = std::max({max, c[0], c[1], c[2]});
    const double full = max <= 255 ? 255.0 : 65535.0;
    cloud.colors_.reserve(rgb.size());
    for (const auto& c : rgb) cloud.colors_.emplace_back(c[0] / full, c[1] / full, c[2] / full);
  }
  if (report) {
    report->version_major = h.major;
    report->version_minor = h.minor;
    report->point_format = h.format;
    report->points = h.points;
    report->has_color = !rgb.empty();
  }
  return cloud;
}

}  // namespace simtree
