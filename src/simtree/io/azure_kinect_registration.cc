// AzureRegistration: the colour image resampled into a pinhole camera, and depth splatted into it.

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/io/azure_kinect.h"

namespace simtree {
namespace {

constexpr float kNone = std::numeric_limits<float>::quiet_NaN();

// Per depth pixel corner ((u - 0.5, v - 0.5) for u in 0..w, v in 0..h), its undistorted ray
// (x, y, 1) turned into the colour camera's axes: the corner at depth z is then z * ray + t.
std::vector<float> CornerRays(const BrownConradyCamera& camera, const Eigen::Matrix3d& rotation) {
  const int w = camera.width + 1;
  const int h = camera.height + 1;
  std::vector<float> rays(static_cast<size_t>(w) * h * 3, kNone);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      const std::optional<Eigen::Vector2d> ray = camera.PixelRay(u - 0.5, v - 0.5);
      if (!ray) continue;
      const Eigen::Vector3d turned = rotation * Eigen::Vector3d(ray->x(), ray->y(), 1.0);
      const size_t i = (static_cast<size_t>(v) * w + u) * 3;
      for (int c = 0; c < 3; ++c) rays[i + c] = static_cast<float>(turned[c]);
    }
  }
  return rays;
}

}  // namespace

// Per pinhole pixel, its bilinear taps in the distorted colour image (computed once, so a frame
// costs four reads and a few multiplies per channel).
std::vector<AzureRegistration::Tap> AzureRegistration::ColorTaps(const BrownConradyCamera& camera) {
  std::vector<Tap> taps(static_cast<size_t>(camera.width) * camera.height);
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d ray((u - camera.cx) / camera.fx, (v - camera.cy) / camera.fy, 1.0);
      const std::optional<Eigen::Vector2d> source = camera.Project(ray);
      if (!source || source->x() < -0.5 || source->y() < -0.5 || source->x() > camera.width - 0.5 ||
          source->y() > camera.height - 0.5) {
        continue;
      }
      // Clamped so the 2x2 taps stay inside; the weights carry the remainder.
      const double x = std::clamp(source->x(), 0.0, camera.width - 1.0);
      const double y = std::clamp(source->y(), 0.0, camera.height - 1.0);
      const int x0 = std::min(static_cast<int>(x), camera.width - 2);
      const int y0 = std::min(static_cast<int>(y), camera.height - 2);
      Tap& t = taps[static_cast<size_t>(v) * camera.width + u];
      t.index = y0 * camera.width + x0;
      t.ax = static_cast<float>(x - x0);
      t.ay = static_cast<float>(y - y0);
    }
  }
  return taps;
}

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
  color_taps_ = ColorTaps(calibration_.color);
  depth_rays_ = CornerRays(calibration_.depth, calibration_.depth_to_color.rotation);
}

RgbImage AzureRegistration::UndistortColor(const RgbImage& color) const {
  if (color.width != calibration_.color.width || color.height != calibration_.color.height) {
    throw InputError("colour image", "",
                     fmt::format("expected {}x{} (the calibration's colour size), got {}x{}",
                                 calibration_.color.width, calibration_.color.height, color.width,
                                 color.height));
  }
  RgbImage out(pinhole_.width, pinhole_.height);
  const uint8_t* in = color.pixels.data();
  const size_t row = static_cast<size_t>(color.width) * 3;
  for (size_t i = 0; i < color_taps_.size(); ++i) {
    const Tap& t = color_taps_[i];
    if (t.index < 0) continue;
    const uint8_t* p = in + static_cast<size_t>(t.index) * 3;
    for (int c = 0; c < 3; ++c) {
      const float top = p[c] + t.ax * (p[3 + c] - p[c]);
      const float bottom = p[row + c] + t.ax * (p[row + 3 + c] - p[row + c]);
      out.pixels[i * 3 + c] = static_cast<uint8_t>(top + t.ay * (bottom - top) + 0.5f);
    }
  }
  return out;
}

DepthImage AzureRegistration::RegisterDepth(const DepthImage& depth) const {
  const BrownConradyCamera& dc = calibration_.depth;
  const Eigen::Vector3d& t = calibration_.depth_to_color.translation_m;
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
        const float* ray =
            &depth_rays_[(static_cast<size_t>(v + corner / 2) * corner_w + u + corner % 2) * 3];
        const double pz = z * ray[2] + t.z();
        if (std::isnan(ray[0]) || pz <= 0) {
          valid = false;
          break;
        }
        const double x = k.fx * (z * ray[0] + t.x()) / pz + k.cx;
        const double y = k.fy * (z * ray[1] + t.y()) / pz + k.cy;
        lo_x = std::min(lo_x, x);
        hi_x = std::max(hi_x, x);
        lo_y = std::min(lo_y, y);
        hi_y = std::max(hi_y, y);
        z_color += pz / 4;
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

RgbImage AzureRegistration::ColorInDepth(const RgbImage& color, const DepthImage& depth) const {
  const BrownConradyCamera& dc = calibration_.depth;
  const BrownConradyCamera& cc = calibration_.color;
  const Eigen::Vector3d& t = calibration_.depth_to_color.translation_m;
  const DepthImage nearest = RegisterDepth(depth);  // what the colour camera sees, for occlusion
  const int corner_w = dc.width + 1;
  RgbImage out(dc.width, dc.height);
  for (int v = 0; v < dc.height; ++v) {
    for (int u = 0; u < dc.width; ++u) {
      const uint16_t mm = depth.at(u, v);
      if (mm == 0) continue;
      // The pixel centre's ray: the mean of its corners' (exact to far below a pixel).
      Eigen::Vector3d ray = Eigen::Vector3d::Zero();
      for (int corner = 0; corner < 4; ++corner) {
        const float* r =
            &depth_rays_[(static_cast<size_t>(v + corner / 2) * corner_w + u + corner % 2) * 3];
        ray += Eigen::Vector3d(r[0], r[1], r[2]) / 4;
      }
      if (!ray.allFinite()) continue;
      const Eigen::Vector3d p = ray * (mm * 0.001) + t;
      const Eigen::Vector2d pin = pinhole_.Project(p);
      const int pu = static_cast<int>(std::lround(pin.x()));
      const int pv = static_cast<int>(std::lround(pin.y()));
      if (pu < 0 || pv < 0 || pu >= pinhole_.width || pv >= pinhole_.height) continue;
      const uint16_t seen = nearest.at(pu, pv);
      if (seen != 0 && seen < p.z() * 1000 * 0.98) continue;  // hidden behind a nearer surface
      const std::optional<Eigen::Vector2d> px = cc.Project(p);
      if (!px || px->x() < 0 || px->y() < 0 || px->x() > cc.width - 1 || px->y() > cc.height - 1) {
        continue;
      }
      const int x0 = std::min(static_cast<int>(px->x()), cc.width - 2);
      const int y0 = std::min(static_cast<int>(px->y()), cc.height - 2);
      const float ax = static_cast<float>(px->x() - x0);
      const float ay = static_cast<float>(px->y() - y0);
      for (int c = 0; c < 3; ++c) {
        const float top =
            color.at(x0, y0, c) + ax * (color.at(x0 + 1, y0, c) - color.at(x0, y0, c));
        const float bottom =
            color.at(x0, y0 + 1, c) + ax * (color.at(x0 + 1, y0 + 1, c) - color.at(x0, y0 + 1, c));
        out.at(u, v, c) = static_cast<uint8_t>(top + ay * (bottom - top) + 0.5f);
      }
    }
  }
  return out;
}

}  // namespace simtree
