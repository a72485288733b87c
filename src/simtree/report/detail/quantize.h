#pragma once
// 16-bit quantisation of positions in their bounding box: what the report sends the animation
// in. Each axis is split into 65535 steps over the box's extent, so a decoded position is within
// half a step of the original (a 4 m tree: 31 µm). Stored little endian, 3 values per point, the
// layout the page reads with a Uint16Array.

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace simtree::report {

inline constexpr int kQuantisationLevels = 65535;

struct QuantisationBox {
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d step = Eigen::Vector3d::Constant(1e-6);  // metres per level, > 0

  // The box of `xyz` (x, y, z per point; non-finite values are skipped). An axis without extent
  // gets a step of 1 µm. Throws InputError for a size that is not a multiple of 3.
  static QuantisationBox Of(std::span<const float> xyz);
  // Grows this box to hold `xyz` too (recomputes the steps).
  void Include(std::span<const float> xyz);

  uint16_t Encode(int axis, double value) const;  // clamped to [0, 65535]
  double Decode(int axis, uint16_t level) const { return min[axis] + step[axis] * level; }
  double max_step() const { return step.maxCoeff(); }

 private:
  Eigen::Vector3d max_ = Eigen::Vector3d::Zero();
  bool empty_ = true;
  void UpdateSteps();
};

// Appends the points of `xyz` to `out` as little-endian uint16 triples (6 bytes a point).
// Non-finite values are written as level 0.
void AppendQuantised(std::span<const float> xyz, const QuantisationBox& box, std::string& out);
// The points back (3 floats per point) from bytes written by AppendQuantised.
std::vector<float> Dequantise(std::string_view bytes, const QuantisationBox& box);

}  // namespace simtree::report
