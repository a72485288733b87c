#include "simtree/report/detail/quantize.h"

#include <algorithm>
#include <cmath>

#include "simtree/core/error.h"

namespace simtree::report {

QuantisationBox QuantisationBox::Of(std::span<const float> xyz) {
  QuantisationBox box;
  box.Include(xyz);
  return box;
}

void QuantisationBox::Include(std::span<const float> xyz) {
  if (xyz.size() % 3 != 0) {
    throw InputError("<positions>", "",
                     "expected x, y, z per point, got " + std::to_string(xyz.size()) + " values");
  }
  for (size_t i = 0; i < xyz.size(); i += 3) {
    const Eigen::Vector3d p(xyz[i], xyz[i + 1], xyz[i + 2]);
    if (!p.allFinite()) continue;
    if (empty_) {
      min = max_ = p;
      empty_ = false;
    } else {
      min = min.cwiseMin(p);
      max_ = max_.cwiseMax(p);
    }
  }
  UpdateSteps();
}

void QuantisationBox::UpdateSteps() {
  for (int a = 0; a < 3; ++a) {
    const double extent = empty_ ? 0.0 : max_[a] - min[a];
    step[a] = extent > 0 ? extent / kQuantisationLevels : 1e-6;
  }
}

uint16_t QuantisationBox::Encode(int axis, double value) const {
  if (!std::isfinite(value)) return 0;
  const double level = std::round((value - min[axis]) / step[axis]);
  return static_cast<uint16_t>(std::clamp(level, 0.0, static_cast<double>(kQuantisationLevels)));
}

void AppendQuantised(std::span<const float> xyz, const QuantisationBox& box, std::string& out) {
  out.reserve(out.size() + xyz.size() * 2);
  for (size_t i = 0; i < xyz.size(); ++i) {
    const uint16_t q = box.Encode(static_cast<int>(i % 3), xyz[i]);
    out += static_cast<char>(q & 0xff);
    out += static_cast<char>(q >> 8);
  }
}

std::vector<float> Dequantise(std::string_view bytes, const QuantisationBox& box) {
  if (bytes.size() % 6 != 0) {
    throw InputError("<quantised positions>", "",
                     "expected 6 bytes per point, got " + std::to_string(bytes.size()) + " bytes");
  }
  std::vector<float> xyz(bytes.size() / 2);
  for (size_t i = 0; i < xyz.size(); ++i) {
    const auto lo = static_cast<uint8_t>(bytes[2 * i]), hi = static_cast<uint8_t>(bytes[2 * i + 1]);
    xyz[i] = static_cast<float>(
        box.Decode(static_cast<int>(i % 3), static_cast<uint16_t>(lo | hi << 8)));
  }
  return xyz;
}

}  // namespace simtree::report
