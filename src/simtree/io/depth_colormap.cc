#include "simtree/io/depth_colormap.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace simtree {
namespace {

// A perceptually ordered ramp (red, orange, yellow, green, cyan, blue, violet), linearly
// interpolated between its stops.
std::array<uint8_t, 3> Ramp(double t) {
  static constexpr std::array<std::array<double, 3>, 7> kStops = {{{230, 40, 30},
                                                                   {245, 140, 30},
                                                                   {240, 220, 50},
                                                                   {90, 200, 90},
                                                                   {40, 180, 200},
                                                                   {40, 90, 220},
                                                                   {110, 50, 170}}};
  const double x = std::clamp(t, 0.0, 1.0) * (kStops.size() - 1);
  const int i = std::min(static_cast<int>(x), static_cast<int>(kStops.size()) - 2);
  const double f = x - i;
  std::array<uint8_t, 3> out{};
  for (int c = 0; c < 3; ++c) {
    out[c] = static_cast<uint8_t>(std::lround((1 - f) * kStops[i][c] + f * kStops[i + 1][c]));
  }
  return out;
}

}  // namespace

RgbImage ColorizeDepth(const DepthImage& depth, const DepthColormapOptions& options) {
  RgbImage out(depth.width, depth.height, 0);
  const double span = std::max(1e-9, options.far_m - options.near_m);
  for (int y = 0; y < depth.height; ++y) {
    for (int x = 0; x < depth.width; ++x) {
      const uint16_t d = depth.at(x, y);
      if (d == 0) continue;
      const auto rgb = Ramp((d * options.depth_scale_m - options.near_m) / span);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = rgb[c];
    }
  }
  return out;
}

}  // namespace simtree
