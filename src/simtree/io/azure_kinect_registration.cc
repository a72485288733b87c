// AzureRegistration: the colour image resampled into a pinhole camera, and depth splatted into it.

#include <algorithm>
#include <cmath>
#include <limits>

#include "simtree/core/option_checks.h"
#include "simtree/io/azure_kinect.h"

namespace simtree {
namespace {

constexpr float kNone = std::numeric_limits<float>::quiet_NaN();

// Per pinhole pixel, where it is in the distorted colour image.
std::vector<float> ColorMap(const BrownConradyCamera& camera) {
  std::vector<float> map(static_cast<size_t>(camera.width) * camera.height * 2, kNone);
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d ray((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1.0);
      const std::optional<Eigen::Vector2d> source = camera.Project(ray);
      if (!source) continue;
      const size_t i = (static_cast<size_t>(v) * camera.width + u) * 2;
      map[i] = static_cast<float>(source->x());
      map[i + 1] = static_cast<float>(source->y());
    }
  }
  return map;
}

// Per depth pixel corner ((u - 0.5, v - 0.5) for u in 0..w, v in 0..h), its undistorted ray.
std::vector<float> CornerRays(const BrownConradyCamera& camera) {
  const int w = camera.width + 1;
  const int h = camera.height + 1;
  std::vector<float> rays(static_cast<size_t>(w) * h * 2, kNone);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const std::optional<Eigen::Vector2d> ray = camera.PixelRay(u - 0.5, v - 0.5);
      if (!ray) continue;
      const size_t i = (static_cast<size_t>(v) * w + u) * 2;
      rays[i] = static_cast<float>(ray->x());
      rays[i + 1] = static_cast<float>(ray->y());
    }
  }
  return rays;
}

uint8_t Bilinear(const RgbImage& image, float x, float y, int channel) {
  const int x0 = static_cast<int>(std::floor(x));
  const int y0 = static_cast<int>(std::floor(y));
  const float ax = x - x0;
  const float ay = y - y0;
  auto at = [&](int xx, int yy) {
    xx = std::clamp(xx, 0, image.width - 1);
    yy = std::clamp(yy, 0, image.height - 1);
    return static_cast<float>(image.at(xx, yy, channel));
  };
  const float top = at(x0, y0) * (1 - ax) + at(x0 + 1, y0) * ax;
  const float bottom = at(x0, y0 + 1) * (1 - ax) + at(x0 + 1, y0 + 1) * ax;
  return static_cast<uint8_t>(std::lround(top * (1 - ay) + bottom * ay));
}

}  // namespace

void AzureRegistrationOptions::Validate() const {
  CheckAtLeast("max_splat_pixels", max_splat_pixels, 1);
  CheckInRange("splat_margin_px", splat_margin_px, 0.0, 1.0);
}

AzureRegistration::AzureRegistration(const AzureCalibration& calibration,
                                     AzureRegistrationOptions options)
    : calibration_(calibration), options_(options) {
  options_.Validate();
  ValidateIntrinsics(calibration_.color.Pinhole(), "colour camera calibration");
  ValidateIntrinsics(calibration_.depth.Pinhole(), "depth camera calibration");
  pinhole_ = calibration_.color.Pinhole();
  color_map_ = ColorMap(calibration_.color);
  depth_rays_ = CornerRays(calibration_.depth);
}

RgbImage AzureRegistration::UndistortColor(const RgbImage& color) const {
  RgbImage out(pinhole_.width, pinhole_.height);
  for (int v = 0; v < out.height; ++v) {
    for (int u = 0; u < out.width; ++u) {
      const size_t i = (static_cast<size_t>(v) * out.width + u) * 2;
      const float x = color_map_[i];
      const float y = color_map_[i + 1];
      if (std::isnan(x) || x < -0.5f || y < -0.5f || x > color.width - 0.5f ||
          y > color.height - 0.5f) {
        continue;
      }
      for (int c = 0; c < 3; ++c) out.at(u, v, c) = Bilinear(color, x, y, c);
    }
  }
  return out;
}

DepthImage AzureRegistration::RegisterDepth(const DepthImage& depth) const {
  const BrownConradyCamera& dc = calibration_.depth;
  const RigidTransform& move = calibration_.depth_to_color;
  const CameraIntrinsics& k = pinhole_;
  const int corner_w = dc.width + 1;
  const int max_side = options_.max_splat_pixels;
  DepthImage out(k.width, k.height, 0);
  for (int v = 0; v < dc.height; ++v) {
    for (int u = 0; u < dc.width; ++u) {
      const uint16_t mm = depth.at(u, v);
      if (mm == 0) continue;
      const double z = mm * 0.001;
      // The pixel's footprint: its four corners at its depth, in the colour image.
      double lo_x = 1e30, lo_y = 1e30, hi_x = -1e30, hi_y = -1e30, z_color = 0;
      bool valid = true;
      for (int corner = 0; corner < 4 && valid; ++corner) {
        const size_t i = (static_cast<size_t>(v + corner / 2) * corner_w + u + corner % 2) * 2;
        if (std::isnan(depth_rays_[i])) {
          valid = false;
          break;
        }
        const Eigen::Vector3d p =
            move.Apply(Eigen::Vector3d(depth_rays_[i] * z, depth_rays_[i + 1] * z, z));
        if (p.z() <= 0) {
          valid = false;
          break;
        }
        const Eigen::Vector2d px = k.Project(p);
        lo_x = std::min(lo_x, px.x());
        hi_x = std::max(hi_x, px.x());
        lo_y = std::min(lo_y, px.y());
        hi_y = std::max(hi_y, px.y());
        z_color += p.z() / 4;
      }
      if (!valid) continue;
      // The colour pixel centres inside the footprint, at most max_side on a side around it.
      const double mid_x = (lo_x + hi_x) / 2, mid_y = (lo_y + hi_y) / 2;
      const double margin = options_.splat_margin_px;
      const double half_x = std::min((hi_x - lo_x) / 2 + margin, max_side / 2.0);
      const double half_y = std::min((hi_y - lo_y) / 2 + margin, max_side / 2.0);
      const int x0 = std::max(0, static_cast<int>(std::ceil(mid_x - half_x)));
      const int x1 = std::min(k.width - 1, static_cast<int>(std::floor(mid_x + half_x)));
      const int y0 = std::max(0, static_cast<int>(std::ceil(mid_y - half_y)));
      const int y1 = std::min(k.height - 1, static_cast<int>(std::floor(mid_y + half_y)));
      const uint16_t value =
          static_cast<uint16_t>(std::clamp(std::lround(z_color * 1000), 1L, 65535L));
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
          uint16_t& cell = out.at(x, y);
          if (cell == 0 || value < cell) cell = value;
        }
      }
    }
  }
  return out;
}

RgbdImage AzureRegistration::Apply(const RgbImage& color, const DepthImage& depth) const {
  RgbdImage out;
  out.color = UndistortColor(color);
  out.depth = RegisterDepth(depth);
  out.intrinsics = pinhole_;
  return out;
}

}  // namespace simtree
