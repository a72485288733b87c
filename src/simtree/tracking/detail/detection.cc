#include "simtree/tracking/detail/detection.h"

#include <algorithm>
#include <cmath>

namespace simtree::tracking::detail {
namespace {

double Median(std::vector<double>& values) {
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  return values[mid];
}

// The tape's chroma along its own hue: linear in RGB, so a pixel that is a share c of tape and
// 1 - c of background lies a share c of the way from the background's value to the tape's.
double Chroma(const uint8_t* rgb, double cos_h, double sin_h) {
  const double a = rgb[0] - 0.5 * (rgb[1] + rgb[2]);
  const double b = 0.8660254037844386 * (rgb[1] - rgb[2]);
  return a * cos_h + b * sin_h;
}

// A tape 3-5 px across at 640 x 576 often has one to three depth pixels, each mixed with what
// lies behind it: on synth's camera-colour streams they read 120-500 mm off the branch, and the
// depth gate refused blobs lying right at the prediction (a quarter of the missed samples). The
// branch around the tape (the blob and its ring) gives a second reading, used only where it
// agrees with the prediction (RemeasureNear): taken as the measurement, it let background depth
// in on other streams.
void AddBranchDepth(const Blob& blob, const std::vector<int>& strong, const RgbdImage& image,
                    const MeasureOptions& options, Detection* det) {
  constexpr int kFewTapeDepths = 4;
  const DepthImage& depth = image.depth;
  const auto has = [&](int i) { return depth.pixels[i] != 0; };
  if (std::count_if(strong.begin(), strong.end(), has) >= kFewTapeDepths) return;
  std::vector<int> all = blob.pixels;
  all.insert(all.end(), blob.ring.begin(), blob.ring.end());
  const double z = RobustDepth(depth, image.intrinsics.depth_scale_m, all, options.edge_m, 0.5);
  if (z <= 0.0) return;
  det->has_branch_depth = true;
  const double z_axis = z + options.axis_offset_ratio * det->radius_m;
  det->branch_position = image.intrinsics.Unproject(det->center.x(), det->center.y(), z_axis);
}

}  // namespace

std::vector<double> TapeCoverage(const Blob& blob, const RgbImage& color, BlobDetector& detector) {
  const double h = detector.model().hue_deg * M_PI / 180.0;
  const double cos_h = std::cos(h), sin_h = std::sin(h);
  std::vector<double> core, background;
  for (int i : blob.pixels) core.push_back(Chroma(&color.pixels[3 * size_t(i)], cos_h, sin_h));
  for (int i : blob.ring) {
    if (detector.WeightAt(color, i) == 0.0f) {
      background.push_back(Chroma(&color.pixels[3 * size_t(i)], cos_h, sin_h));
    }
  }
  std::vector<double> sorted = core;
  std::sort(sorted.begin(), sorted.end());
  const double tape = sorted[std::min(sorted.size() - 1, (3 * sorted.size()) / 4)];
  const double back = background.empty() ? 0.0 : Median(background);
  const double span = std::max(1.0, tape - back);
  std::vector<double> out;
  out.reserve(blob.pixels.size() + blob.ring.size());
  for (const std::vector<int>* list : {&blob.pixels, &blob.ring}) {
    for (int i : *list) {
      const double c = (Chroma(&color.pixels[3 * size_t(i)], cos_h, sin_h) - back) / span;
      out.push_back(std::clamp(c, 0.0, 1.0));
    }
  }
  return out;
}

double RobustDepth(const DepthImage& depth, double depth_scale_m, const std::vector<int>& pixels,
                   double edge_m, double quantile) {
  const double edge_units = edge_m / depth_scale_m;
  std::vector<double> inner, all;
  for (int i : pixels) {
    const uint16_t d = depth.pixels[i];
    if (d == 0) continue;
    all.push_back(d);
    if (!OnDepthEdge(depth, i % depth.width, i / depth.width, edge_units)) inner.push_back(d);
  }
  std::vector<double>& use = inner.size() >= 2 ? inner : all;
  if (use.empty()) return 0.0;
  const double first = Median(use);
  // Drop what is far from the first median (a background pixel seen through a gap), then take
  // the quantile of the rest.
  std::vector<double> near;
  for (double d : use) {
    if (std::abs(d - first) <= 0.5 * edge_units) near.push_back(d);
  }
  double second = first;
  if (!near.empty()) {
    std::sort(near.begin(), near.end());
    second = near[std::min(near.size() - 1, static_cast<size_t>(quantile * near.size()))];
  }
  return second * depth_scale_m;
}

bool RemeasureNear(const Detection& det, const CameraIntrinsics& intrinsics, double z_axis,
                   double window_m, Eigen::Vector3d* position) {
  if (!det.has_depth) return false;
  const double offset = det.position.z() - det.front_m;
  std::vector<double> near;
  for (double d : det.depths_m) {
    if (std::abs(d + offset - z_axis) <= window_m) near.push_back(d);
  }
  // Enough of the tape agrees with the prediction: at least two pixels and a quarter of them;
  // else the branch around a tape with few depth pixels, when it agrees.
  if (near.size() < 2 || 4 * near.size() < det.depths_m.size()) {
    if (!det.has_branch_depth || std::abs(det.branch_position.z() - z_axis) > window_m) {
      return false;
    }
    *position = det.branch_position;
    return true;
  }
  const double front =
      near[std::min(near.size() - 1, static_cast<size_t>(det.depth_quantile * near.size()))];
  *position = intrinsics.Unproject(det.center.x(), det.center.y(), front + offset);
  return true;
}

Detection MeasureBlob(const Blob& blob, const RgbdImage& image, BlobDetector& detector,
                      const MeasureOptions& options) {
  Detection det;
  det.pixel_count = static_cast<int>(blob.pixels.size());
  det.source = blob.source;
  const int width = image.color.width;
  const std::vector<double> coverage = TapeCoverage(blob, image.color, detector);
  std::vector<Eigen::Vector2d> points;
  points.reserve(coverage.size());
  for (const std::vector<int>* list : {&blob.pixels, &blob.ring}) {
    for (int i : *list) points.emplace_back(i % width, i / width);
  }
  for (double c : coverage) det.weight += c;
  det.shape = det.weight > 0.0 ? MeasureBandShape(points, coverage, options.blur_var_px2)
                               : BandShape{.center = points.front()};
  det.center = det.shape.center;

  const CameraIntrinsics& k = image.intrinsics;
  // Depth from the pixels that are mostly tape (a mixed pixel's depth may be the background's).
  std::vector<int> strong;
  for (int i : blob.pixels) {
    if (detector.WeightAt(image.color, i) >= kCleanWeight) strong.push_back(i);
  }
  const double z_surface =
      RobustDepth(image.depth, k.depth_scale_m, strong.size() >= 2 ? strong : blob.pixels,
                  options.edge_m, options.depth_quantile);
  for (int i : strong.size() >= 2 ? strong : blob.pixels) {
    if (image.depth.pixels[i] != 0) det.depths_m.push_back(image.depth.pixels[i] * k.depth_scale_m);
  }
  std::sort(det.depths_m.begin(), det.depths_m.end());
  det.depth_quantile = options.depth_quantile;
  if (z_surface > 0.0) {
    det.has_depth = true;
    // The axis offset was chosen with the tape's width as the camera blurs it: any blur taken off
    // the band is put back.
    const Eigen::Vector2d across(-det.shape.axis.y(), det.shape.axis.x());
    const double blur = options.blur_var_px2.dot(across.cwiseProduct(across));
    const double radius_px = std::sqrt(det.shape.radius * det.shape.radius + 3.0 * blur);
    det.radius_m = std::clamp(radius_px * z_surface / k.fx, 0.002, 0.06);
    det.front_m = z_surface;
    const double z_axis = z_surface + options.axis_offset_ratio * det.radius_m;
    det.position = k.Unproject(det.center.x(), det.center.y(), z_axis);
    AddBranchDepth(blob, strong, image, options, &det);
  }
  return det;
}

}  // namespace simtree::tracking::detail
