#pragma once
// LAS files after the ASPRS specification's header layout (versions 1.2-1.4, point formats 0-3 and
// 6-8, scale and offset, colour, variable length records before the points, extra bytes per
// record), for the LAS reader's tests and fuzz seeds.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace simtree::test {

struct LasPoint {
  int32_t x, y, z;
  uint16_t r = 0, g = 0, b = 0;
};

struct LasSpec {
  int minor = 2;
  int format = 0;
  int extra_bytes = 0;  // after the format's fields
  int vlr_bytes = 0;    // between the header and the points
  double scale[3] = {0.001, 0.001, 0.01};
  double offset[3] = {100, 200, 10};
};

// The header's byte offsets the tests change: the point format and the legacy point count.
constexpr size_t kLasPointFormatAt = 104;
constexpr size_t kLasLegacyCountAt = 107;

std::string LasBytes(const LasSpec& spec, const std::vector<LasPoint>& points);
std::filesystem::path WriteLas(const std::filesystem::path& path, const LasSpec& spec,
                               const std::vector<LasPoint>& points);

}  // namespace simtree::test
