#include "simtree/preprocessing/depth_to_cloud.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"

namespace simtree::preprocessing {
namespace {

// True when no 8-neighbour of (u, v) has a depth near the pixel's own.
bool IsFlying(const DepthImage& depth, int u, int v, double scale,
              const DepthToCloudOptions& options) {
  const double z = depth.at(u, v) * scale;
  const double jump = std::max(options.flying_min_jump_m, options.flying_jump_share * z);
  for (int dv = -1; dv <= 1; ++dv) {
    for (int du = -1; du <= 1; ++du) {
      if (du == 0 && dv == 0) continue;
      const int x = u + du, y = v + dv;
      if (x < 0 || y < 0 || x >= depth.width || y >= depth.height) continue;
      const uint16_t raw = depth.at(x, y);
      if (raw != 0 && std::abs(raw * scale - z) <= jump) return false;
    }
  }
  return true;
}

}  // namespace

void DepthToCloudOptions::Validate() const {
  CheckNonNegative("min_depth_m", min_depth_m);
  CheckOrdered("min_depth_m", min_depth_m, "max_depth_m", max_depth_m);
  CheckAtLeast("stride", stride, 1);
  CheckNonNegative("flying_min_jump_m", flying_min_jump_m);
  CheckShare("flying_jump_share", flying_jump_share);
}

open3d::geometry::PointCloud DepthToCloud(const RgbdImage& image,
                                          const DepthToCloudOptions& options,
                                          const std::string& source) {
  options.Validate();
  ValidateIntrinsics(image.intrinsics, source);
  const CameraIntrinsics& k = image.intrinsics;
  if (image.depth.width != k.width || image.depth.height != k.height) {
    throw InputError(source, "depth",
                     fmt::format("expected a {}x{} depth image (the intrinsics' size), got {}x{}",
                                 k.width, k.height, image.depth.width, image.depth.height));
  }
  const bool colors = options.with_colors && !image.color.empty();
  if (colors && (image.color.width != k.width || image.color.height != k.height)) {
    throw InputError(source, "color",
                     fmt::format("expected a {}x{} colour image registered to the depth, got {}x{}",
                                 k.width, k.height, image.color.width, image.color.height));
  }

  open3d::geometry::PointCloud cloud;
  cloud.points_.reserve(image.depth.pixel_count() / (options.stride * options.stride) / 2);
  for (int v = 0; v < k.height; v += options.stride) {
    for (int u = 0; u < k.width; u += options.stride) {
      const uint16_t raw = image.depth.at(u, v);
      if (raw == 0) continue;
      const double z = raw * k.depth_scale_m;
      if (z < options.min_depth_m || z > options.max_depth_m) continue;
      if (options.flying_min_jump_m > 0 && IsFlying(image.depth, u, v, k.depth_scale_m, options)) {
        continue;
      }
      cloud.points_.push_back(k.Unproject(u, v, z));
      if (colors) {
        cloud.colors_.emplace_back(image.color.at(u, v, 0) / 255.0, image.color.at(u, v, 1) / 255.0,
                                   image.color.at(u, v, 2) / 255.0);
      }
    }
  }
  return cloud;
}

}  // namespace simtree::preprocessing
