#include "simtree/synth/rgbd_false_color.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "simtree/synth/sensor_random.h"

namespace simtree {
namespace {

// A rainbow from red (near) through yellow, green and cyan to blue and violet (far), as
// piecewise-linear stops.
std::array<uint8_t, 3> Rainbow(double t) {
  static constexpr std::array<std::array<double, 3>, 6> kStops = {{{0.85, 0.10, 0.10},
                                                                   {0.95, 0.75, 0.15},
                                                                   {0.35, 0.80, 0.25},
                                                                   {0.15, 0.75, 0.80},
                                                                   {0.15, 0.30, 0.90},
                                                                   {0.45, 0.15, 0.60}}};
  const double x = std::clamp(t, 0.0, 1.0) * (kStops.size() - 1);
  const size_t i = std::min(static_cast<size_t>(x), kStops.size() - 2);
  const double f = x - i;
  std::array<uint8_t, 3> out{};
  for (int c = 0; c < 3; ++c) {
    out[c] = static_cast<uint8_t>(
        std::lround(255.0 * (kStops[i][c] + f * (kStops[i + 1][c] - kStops[i][c]))));
  }
  return out;
}

}  // namespace

RgbImage ColorizeDepth(const DepthImage& depth, double near_m, double far_m, double depth_scale_m) {
  RgbImage out(depth.width, depth.height);
  const double span = std::max(far_m - near_m, 1e-9);
  for (size_t i = 0; i < depth.pixels.size(); ++i) {
    if (depth.pixels[i] == 0) continue;
    const auto c = Rainbow((depth.pixels[i] * depth_scale_m - near_m) / span);
    for (int k = 0; k < 3; ++k) out.pixels[3 * i + k] = c[k];
  }
  return out;
}

RgbImage ColorizeLabels(const LabelImage& labels) {
  RgbImage out(labels.width, labels.height);
  for (size_t i = 0; i < labels.pixels.size(); ++i) {
    const PixelLabel& l = labels.pixels[i];
    std::array<uint8_t, 3> c = {0, 0, 0};
    switch (l.kind) {
      case SurfaceKind::kNone:
        c = {200, 220, 240};
        break;
      case SurfaceKind::kGround:
        c = {90, 70, 50};
        break;
      case SurfaceKind::kBackground:
        c = {40, 80, 40};
        break;
      case SurfaceKind::kRope:
        c = {255, 230, 0};
        break;
      case SurfaceKind::kOccluder:
        c = {255, 0, 255};
        break;
      case SurfaceKind::kBranch: {
        if (l.marker >= 0) {
          c = {255, 0, 0};
        } else {  // a stable colour per branch, away from pure red
          const uint64_t h = MixBits(static_cast<uint64_t>(l.branch));
          c = {static_cast<uint8_t>(40 + (h & 0x7F)), static_cast<uint8_t>(80 + ((h >> 8) & 0x7F)),
               static_cast<uint8_t>(80 + ((h >> 16) & 0x7F))};
        }
        break;
      }
    }
    for (int k = 0; k < 3; ++k) out.pixels[3 * i + k] = c[k];
  }
  return out;
}

}  // namespace simtree
