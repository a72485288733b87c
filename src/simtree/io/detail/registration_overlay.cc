#include "simtree/io/detail/registration_overlay.h"

#include <cstdlib>
#include <utility>

#include "simtree/io/depth_colormap.h"

namespace simtree::azure_detail {
namespace {

constexpr int kEdgeJumpMm = 50;

bool DepthEdge(const DepthImage& d, int x, int y) {
  const int a = d.at(x, y);
  if (a == 0) return false;
  for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
    if (x + dx >= d.width || y + dy >= d.height) continue;
    const int b = d.at(x + dx, y + dy);
    if (b != 0 && std::abs(a - b) > kEdgeJumpMm) return true;
  }
  return false;
}

}  // namespace

RgbImage RegistrationOverlay(const RgbImage& color, const DepthImage& depth_in_color) {
  DepthColormapOptions ramp;
  ramp.near_m = 0.3;
  ramp.far_m = 4.0;
  const RgbImage false_color = ColorizeDepth(depth_in_color, ramp);
  const int w = color.width / 2;
  const int h = color.height / 2;
  RgbImage out(2 * w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      // Each output pixel shows one source pixel of its 2x2 block, so thin edges stay sharp;
      // an edge anywhere in the block is drawn.
      const int sx = 2 * x, sy = 2 * y;
      const bool has_depth = depth_in_color.at(sx, sy) != 0;
      const bool edge =
          DepthEdge(depth_in_color, sx, sy) || DepthEdge(depth_in_color, sx + 1, sy) ||
          DepthEdge(depth_in_color, sx, sy + 1) || DepthEdge(depth_in_color, sx + 1, sy + 1);
      for (int c = 0; c < 3; ++c) {
        const int rgb = color.at(sx, sy, c);
        out.at(x, y, c) =
            static_cast<uint8_t>(has_depth ? (rgb + false_color.at(sx, sy, c)) / 2 : rgb / 3);
        out.at(w + x, y, c) = edge ? static_cast<uint8_t>(c == 1 ? 255 : 0) : color.at(sx, sy, c);
      }
    }
  }
  return out;
}

}  // namespace simtree::azure_detail
