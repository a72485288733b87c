#include "support/las_writer.h"

#include <cstring>

#include "simtree/core/atomic_file.h"

namespace simtree::test {
namespace {

template <typename T>
void Put(std::string& bytes, size_t at, T value) {
  std::memcpy(bytes.data() + at, &value, sizeof(T));
}

int BaseLength(int format) {
  const int lengths[] = {20, 28, 26, 34, 0, 0, 30, 36, 38};
  return lengths[format];
}
int ColorOffset(int format) {
  const int offsets[] = {-1, -1, 20, 28, -1, -1, -1, 30, 30};
  return offsets[format];
}

}  // namespace

std::string LasBytes(const LasSpec& spec, const std::vector<LasPoint>& points) {
  const int header = spec.minor >= 4 ? 375 : spec.minor == 3 ? 235 : 227;
  const int record = BaseLength(spec.format) + spec.extra_bytes;
  std::string bytes(header + spec.vlr_bytes + record * points.size(), '\0');
  std::memcpy(bytes.data(), "LASF", 4);
  bytes[24] = 1;
  bytes[25] = static_cast<char>(spec.minor);
  Put<uint16_t>(bytes, 94, static_cast<uint16_t>(header));
  Put<uint32_t>(bytes, 96, static_cast<uint32_t>(header + spec.vlr_bytes));
  Put<uint32_t>(bytes, 100, spec.vlr_bytes > 0 ? 1 : 0);
  bytes[kLasPointFormatAt] = static_cast<char>(spec.format);
  Put<uint16_t>(bytes, 105, static_cast<uint16_t>(record));
  // LAS 1.4 keeps the legacy count 0 for formats 6-10 and the count in a 64-bit field.
  if (spec.format < 6)
    Put<uint32_t>(bytes, kLasLegacyCountAt, static_cast<uint32_t>(points.size()));
  if (spec.minor >= 4) Put<uint64_t>(bytes, 247, points.size());
  for (int k = 0; k < 3; ++k) {
    Put<double>(bytes, 131 + 8 * k, spec.scale[k]);
    Put<double>(bytes, 155 + 8 * k, spec.offset[k]);
  }
  for (size_t i = 0; i < points.size(); ++i) {
    const size_t at = header + spec.vlr_bytes + i * record;
    Put<int32_t>(bytes, at, points[i].x);
    Put<int32_t>(bytes, at + 4, points[i].y);
    Put<int32_t>(bytes, at + 8, points[i].z);
    Put<uint16_t>(bytes, at + 12, 7777);  // intensity: must not leak into anything
    if (ColorOffset(spec.format) >= 0) {
      Put<uint16_t>(bytes, at + ColorOffset(spec.format), points[i].r);
      Put<uint16_t>(bytes, at + ColorOffset(spec.format) + 2, points[i].g);
      Put<uint16_t>(bytes, at + ColorOffset(spec.format) + 4, points[i].b);
    }
  }
  return bytes;
}

std::filesystem::path WriteLas(const std::filesystem::path& path, const LasSpec& spec,
                               const std::vector<LasPoint>& points) {
  WriteFileAtomically(path, LasBytes(spec, points));
  return path;
}

}  // namespace simtree::test
