#include "simtree/synth/detail/depth_to_color.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "simtree/core/error.h"

namespace simtree::synth {
namespace {

// Half a depth pixel, and a little more: neighbours on a slanted surface have different depths,
// so their footprints' shared edge moves apart by a few hundredths of a colour pixel through the
// 32 mm parallax; the overlap closes those slivers (the z-buffer settles it).
constexpr double kHalfFootprint = 0.6;

}  // namespace

DepthImage RegisterDepthToColor(const DepthImage& depth, const CameraIntrinsics& depth_intrinsics,
                                const CameraIntrinsics& color_intrinsics,
                                const Eigen::Isometry3d& color_from_depth) {
  ValidateIntrinsics(depth_intrinsics, "depth intrinsics");
  ValidateIntrinsics(color_intrinsics, "colour intrinsics");
  if (depth.width != depth_intrinsics.width || depth.height != depth_intrinsics.height) {
    throw InputError("depth to colour", "depth",
                     fmt::format("expected a {}x{} depth image, got {}x{}", depth_intrinsics.width,
                                 depth_intrinsics.height, depth.width, depth.height));
  }
  const CameraIntrinsics& kd = depth_intrinsics;
  const CameraIntrinsics& kc = color_intrinsics;
  const double scale = kd.depth_scale_m;
  const double unit = 1.0 / kc.depth_scale_m;
  const double max_z = std::numeric_limits<uint16_t>::max() / unit;
  // Nearest z (metres) per colour pixel; infinity: no depth.
  std::vector<float> nearest(static_cast<size_t>(kc.width) * kc.height,
                             std::numeric_limits<float>::infinity());
  const Eigen::Matrix3d rotation = color_from_depth.linear();
  const Eigen::Vector3d translation = color_from_depth.translation();
  for (int y = 0; y < kd.height; ++y) {
    for (int x = 0; x < kd.width; ++x) {
      const uint16_t d = depth.at(x, y);
      if (d == 0) continue;
      const double z = d * scale;
      const Eigen::Vector3d centre = rotation * kd.Unproject(x, y, z) + translation;
      if (centre.z() <= 0.0 || centre.z() > max_z) continue;
      double u0 = std::numeric_limits<double>::infinity(), u1 = -u0, v0 = u0, v1 = -u0;
      for (const double dx : {-kHalfFootprint, kHalfFootprint}) {
        for (const double dy : {-kHalfFootprint, kHalfFootprint}) {
          const Eigen::Vector3d corner = rotation * kd.Unproject(x + dx, y + dy, z) + translation;
          if (corner.z() <= 0.0) continue;
          const Eigen::Vector2d uv = kc.Project(corner);
          u0 = std::min(u0, uv.x());
          u1 = std::max(u1, uv.x());
          v0 = std::min(v0, uv.y());
          v1 = std::max(v1, uv.y());
        }
      }
      // Colour pixel centres (integers) in [u0, u1) x [v0, v1), inside the image.
      const int first_u = std::max(0, static_cast<int>(std::ceil(u0)));
      const int last_u = std::min(kc.width - 1, static_cast<int>(std::ceil(u1)) - 1);
      const int first_v = std::max(0, static_cast<int>(std::ceil(v0)));
      const int last_v = std::min(kc.height - 1, static_cast<int>(std::ceil(v1)) - 1);
      const auto zc = static_cast<float>(centre.z());
      for (int v = first_v; v <= last_v; ++v) {
        float* row = &nearest[static_cast<size_t>(v) * kc.width];
        for (int u = first_u; u <= last_u; ++u) row[u] = std::min(row[u], zc);
      }
    }
  }
  DepthImage out(kc.width, kc.height);
  for (size_t i = 0; i < nearest.size(); ++i) {
    if (std::isfinite(nearest[i])) {
      out.pixels[i] = static_cast<uint16_t>(std::lround(nearest[i] * unit));
    }
  }
  return out;
}

}  // namespace simtree::synth
