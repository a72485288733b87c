#include "simtree/synth/detail/rgbd_false_color.h"

#include <array>

#include "simtree/synth/detail/sensor_random.h"

namespace simtree::synth {

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

}  // namespace simtree::synth
