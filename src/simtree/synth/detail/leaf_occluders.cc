#include "simtree/synth/detail/leaf_occluders.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/synth/detail/sensor_random.h"

namespace simtree::synth {

Eigen::Vector2d LeafOccluder::CentreAt(double time_s) const {
  return centre + amplitude_px * std::sin(2.0 * std::numbers::pi * time_s / period_s + phase_rad) *
                      direction;
}

void LeafOccluderOptions::Validate() const {
  if (count < 0 || count > 50) {
    throw InputError("leaf occluder options", "count", fmt::format("expected 0-50, got {}", count));
  }
  if (!(pixel_scale > 0.1 && pixel_scale < 10.0)) {
    throw InputError("leaf occluder options", "pixel_scale",
                     fmt::format("expected (0.1, 10), got {}", pixel_scale));
  }
}

std::vector<LeafOccluder> PlanLeafOccluders(const MarkerFrame2d& first_frame,
                                            const LeafOccluderOptions& options) {
  options.Validate();
  std::vector<const MarkerBox2d*> visible;
  for (const MarkerBox2d& m : first_frame.markers) {
    if (m.visible) visible.push_back(&m);
  }
  std::vector<LeafOccluder> leaves;
  if (visible.empty()) return leaves;
  PixelRandom random(options.seed, 0, 0, RandomStream::kScene);
  // Markers spread over the list, so the leaves hang in front of different parts of the tree.
  for (int k = 0; k < options.count; ++k) {
    const MarkerBox2d& m = *visible[(k * visible.size()) / options.count % visible.size()];
    LeafOccluder leaf;
    const double angle = std::numbers::pi * random.Uniform();
    leaf.direction = Eigen::Vector2d(std::cos(angle), std::sin(angle));
    leaf.amplitude_px = options.pixel_scale * (20.0 + 20.0 * random.Uniform());
    // The swing's middle off the marker, so the leaf covers it twice a period, on its way to
    // one end of the swing and back; at the first frame it is at the other end, clear of the
    // tape (a person clicks the markers they see).
    leaf.centre = Eigen::Vector2d(m.box[0] + 0.5 * m.box[2], m.box[1] + 0.5 * m.box[3]) +
                  (0.3 + 0.3 * random.Uniform()) * leaf.amplitude_px * leaf.direction;
    leaf.period_s = 1.5 + 2.0 * random.Uniform();
    leaf.phase_rad = 0.5 * std::numbers::pi;
    leaf.half_length_px = options.pixel_scale * (9.0 + 5.0 * random.Uniform());
    leaf.half_width_px = 0.5 * leaf.half_length_px;
    leaf.depth_m = 0.8 + 0.4 * random.Uniform();
    const float shade = static_cast<float>(0.7 + 0.6 * random.Uniform());
    leaf.color = Eigen::Vector3f(0.16f, 0.30f, 0.08f) * shade;
    leaves.push_back(leaf);
  }
  return leaves;
}

void DrawLeafOccluders(const std::vector<LeafOccluder>& leaves, double time_s, RgbImage& color,
                       DepthImage& depth, LabelImage& labels) {
  if (color.width != depth.width || color.height != depth.height || labels.width != color.width ||
      labels.height != color.height) {
    throw InputError("<memory>", "leaf occluders",
                     fmt::format("expected colour, depth and labels of one size, got {}x{}, "
                                 "{}x{}, {}x{}",
                                 color.width, color.height, depth.width, depth.height, labels.width,
                                 labels.height));
  }
  for (const LeafOccluder& leaf : leaves) {
    const Eigen::Vector2d c = leaf.CentreAt(time_s);
    // The leaf's long axis along the swing.
    const Eigen::Vector2d u = leaf.direction;
    const Eigen::Vector2d v(-u.y(), u.x());
    const double reach = leaf.half_length_px + 1.0;
    const int x0 = std::max(0, static_cast<int>(std::floor(c.x() - reach)));
    const int x1 = std::min(color.width - 1, static_cast<int>(std::ceil(c.x() + reach)));
    const int y0 = std::max(0, static_cast<int>(std::floor(c.y() - reach)));
    const int y1 = std::min(color.height - 1, static_cast<int>(std::ceil(c.y() + reach)));
    const auto depth_mm = static_cast<uint16_t>(std::lround(1000.0 * leaf.depth_m));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const Eigen::Vector2d d = Eigen::Vector2d(x, y) - c;
        const double a = d.dot(u) / leaf.half_length_px;
        const double b = d.dot(v) / leaf.half_width_px;
        if (a * a + b * b > 1.0) continue;
        // Lighter along the midrib, darker at the rim.
        const float light = static_cast<float>(1.0 - 0.3 * (a * a + b * b));
        for (int ch = 0; ch < 3; ++ch) {
          color.at(x, y, ch) = static_cast<uint8_t>(
              std::clamp(255.0f * leaf.color[ch] * light, 0.0f, 255.0f) + 0.5f);
        }
        depth.at(x, y) = depth_mm;
        PixelLabel& label = labels.at(x, y);
        label = PixelLabel{};
        label.kind = SurfaceKind::kOccluder;
        label.depth_m = static_cast<float>(leaf.depth_m);
      }
    }
  }
}

}  // namespace simtree::synth
