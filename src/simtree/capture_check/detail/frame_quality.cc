#include "simtree/capture_check/detail/frame_quality.h"

#include <algorithm>
#include <cmath>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "simtree/tracking/find_tapes.h"

namespace simtree::capture_check::detail {

namespace {

constexpr double kDepthAgreementM = 0.15;  // a pixel this near a tree point's depth is the tree's
constexpr int kHoleSpanPx = 3;             // a hole is bounded by tree pixels this close
constexpr int kClippedLevel = 250;

// Marks the pixels of the tree: around each point's projection, those whose depth agrees.
std::vector<uint8_t> TreeMask(const RgbdImage& image, const open3d::geometry::PointCloud& tree,
                              double spacing_m, std::vector<double>* depths) {
  const CameraIntrinsics& k = image.intrinsics;
  const DepthImage& depth = image.depth;
  std::vector<uint8_t> mask(depth.pixel_count(), 0);
  for (const Eigen::Vector3d& p : tree.points_) {
    if (!(p.z() > 0)) continue;
    depths->push_back(p.z());
    const Eigen::Vector2d uv = k.Project(p);
    const int r = std::clamp(static_cast<int>(std::ceil(0.5 * spacing_m * k.fx / p.z())), 1, 8);
    const int u0 = static_cast<int>(std::lround(uv.x())),
              v0 = static_cast<int>(std::lround(uv.y()));
    for (int v = std::max(0, v0 - r); v <= std::min(depth.height - 1, v0 + r); ++v) {
      for (int u = std::max(0, u0 - r); u <= std::min(depth.width - 1, u0 + r); ++u) {
        const uint16_t d = depth.at(u, v);
        if (d > 0 && std::abs(d * k.depth_scale_m - p.z()) < kDepthAgreementM) {
          mask[static_cast<size_t>(v) * depth.width + u] = 1;
        }
      }
    }
  }
  return mask;
}

// Whether a tree pixel lies within kHoleSpanPx of (x, y) in direction (dx, dy).
bool TreeWithin(const std::vector<uint8_t>& mask, int w, int h, int x, int y, int dx, int dy) {
  for (int s = 1; s <= kHoleSpanPx; ++s) {
    const int u = x + s * dx, v = y + s * dy;
    if (u < 0 || v < 0 || u >= w || v >= h) return false;
    if (mask[static_cast<size_t>(v) * w + u] == 1) return true;
  }
  return false;
}

// Marks (2) the pixels without depth enclosed by tree pixels in a row or a column.
int MarkHoles(const DepthImage& depth, std::vector<uint8_t>* mask) {
  const int w = depth.width, h = depth.height;
  int holes = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (depth.at(x, y) != 0) continue;
      const bool row = TreeWithin(*mask, w, h, x, y, -1, 0) && TreeWithin(*mask, w, h, x, y, 1, 0);
      const bool col = TreeWithin(*mask, w, h, x, y, 0, -1) && TreeWithin(*mask, w, h, x, y, 0, 1);
      if (row || col) {
        (*mask)[static_cast<size_t>(y) * w + x] = 2;
        ++holes;
      }
    }
  }
  return holes;
}

void MeasureExposure(const RgbImage& color, const std::vector<uint8_t>& mask, FrameQuality* q) {
  // Darker pixels have no hue the tracker can read.
  const double dark_level = tracking::TapeMinBrightness();
  int n = 0, bright = 0, dark = 0;
  for (size_t i = 0; i < mask.size(); ++i) {
    if (mask[i] == 0) continue;
    const uint8_t* c = &color.pixels[i * 3];
    const int hi = std::max({c[0], c[1], c[2]});
    ++n;
    bright += hi >= kClippedLevel;
    dark += hi < dark_level;
  }
  q->bright_share = n > 0 ? static_cast<double>(bright) / n : 0;
  q->dark_share = n > 0 ? static_cast<double>(dark) / n : 0;
}

}  // namespace

namespace {

// The blur effect along one direction (dx, dy: a row or a column step) of `grey` against the
// same image blurred by `box` along it, over the mask's pixels whose neighbour is in the mask.
double DirectionalBlur(const cv::Mat& grey, const cv::Mat& box, const std::vector<uint8_t>& mask,
                       int dx, int dy) {
  double original = 0, kept_by_blur = 0;
  for (int y = dy; y < grey.rows; ++y) {
    const uint8_t* g = grey.ptr<uint8_t>(y);
    const uint8_t* g_prev = grey.ptr<uint8_t>(y - dy);
    const float* b = box.ptr<float>(y);
    const float* b_prev = box.ptr<float>(y - dy);
    for (int x = dx; x < grey.cols; ++x) {
      const size_t i = static_cast<size_t>(y) * grey.cols + x;
      const size_t j = static_cast<size_t>(y - dy) * grey.cols + (x - dx);
      if (mask[i] == 0 || mask[j] == 0) continue;
      const double d_original = std::abs(static_cast<double>(g[x]) - g_prev[x - dx]);
      const double d_blurred = std::abs(static_cast<double>(b[x]) - b_prev[x - dx]);
      original += d_original;
      kept_by_blur += std::min(d_original, d_blurred);
    }
  }
  return original > 0 ? kept_by_blur / original : 0;
}

}  // namespace

double BlurEffect(const RgbImage& color, const std::vector<uint8_t>& mask) {
  if (color.empty() || mask.size() != color.pixel_count()) return 0;
  // Re-blurred at the scale of the thinnest tapes the tracker reads (2-4 px): the blur that
  // loses them is what matters (bench/capture_check_blur.sh).
  constexpr int kBoxPx = 3;
  cv::Mat rgb(color.height, color.width, CV_8UC3, const_cast<uint8_t*>(color.pixels.data()));
  cv::Mat grey, along_rows, along_columns;
  cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
  cv::blur(grey, along_rows, cv::Size(kBoxPx, 1));
  cv::blur(grey, along_columns, cv::Size(1, kBoxPx));
  along_rows.convertTo(along_rows, CV_32F);
  along_columns.convertTo(along_columns, CV_32F);
  return std::max(DirectionalBlur(grey, along_rows, mask, 1, 0),
                  DirectionalBlur(grey, along_columns, mask, 0, 1));
}

FrameQuality MeasureFrame(const RgbdImage& image, const open3d::geometry::PointCloud& tree_camera,
                          double point_spacing_m) {
  FrameQuality q;
  std::vector<double> depths;
  std::vector<uint8_t> mask = TreeMask(image, tree_camera, point_spacing_m, &depths);
  q.tree_pixels = static_cast<int>(std::count(mask.begin(), mask.end(), uint8_t{1}));
  q.hole_pixels = MarkHoles(image.depth, &mask);
  const int all = q.tree_pixels + q.hole_pixels;
  q.depth_share = all > 0 ? static_cast<double>(q.tree_pixels) / all : 0;
  if (!depths.empty()) {
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
    q.distance_m = depths[depths.size() / 2];
  }
  q.blur = BlurEffect(image.color, mask);
  MeasureExposure(image.color, mask, &q);
  return q;
}

}  // namespace simtree::capture_check::detail
