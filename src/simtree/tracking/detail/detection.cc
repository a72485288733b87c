#include "simtree/tracking/detail/detection.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace simtree::tracking::detail {
namespace {

double Median(std::vector<double>& values) {
  const size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + mid, values.end());
  return values[mid];
}

bool OnDepthEdge(const DepthImage& depth, int x, int y, double edge_units) {
  const double d = depth.at(x, y);
  const int dx[4] = {1, -1, 0, 0};
  const int dy[4] = {0, 0, 1, -1};
  for (int k = 0; k < 4; ++k) {
    const int nx = x + dx[k], ny = y + dy[k];
    if (nx < 0 || ny < 0 || nx >= depth.width || ny >= depth.height) continue;
    const double n = depth.at(nx, ny);
    if (n == 0.0 || std::abs(n - d) > edge_units) return true;
  }
  return false;
}

}  // namespace

double RobustDepth(const DepthImage& depth, double depth_scale_m, const std::vector<int>& pixels,
                   double edge_m) {
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
  // Drop what is far from the first median (a background pixel seen through a gap), then again.
  std::vector<double> near;
  for (double d : use) {
    if (std::abs(d - first) <= 0.5 * edge_units) near.push_back(d);
  }
  const double second = near.empty() ? first : Median(near);
  return second * depth_scale_m;
}

Detection MeasureBlob(const Blob& blob, const RgbdImage& image, BlobDetector& detector,
                      const MeasureOptions& options) {
  Detection det;
  det.pixel_count = static_cast<int>(blob.pixels.size());
  const int width = image.color.width;
  double sw = 0.0;
  Eigen::Vector2d s1 = Eigen::Vector2d::Zero();
  Eigen::Matrix2d s2 = Eigen::Matrix2d::Zero();
  const auto add = [&](int i, double w) {
    const Eigen::Vector2d p(i % width, i / width);
    sw += w;
    s1 += w * p;
    s2 += w * p * p.transpose();
  };
  for (int i : blob.pixels) add(i, std::max(0.5f, detector.WeightAt(image.color, i)));
  for (int i : blob.ring) add(i, detector.WeightAt(image.color, i));
  det.weight = sw;
  det.center = s1 / sw;
  const Eigen::Matrix2d cov = s2 / sw - det.center * det.center.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  Eigen::Vector2d half = Eigen::Vector2d::Zero();
  Eigen::Vector2d semi;  // the rectangle's half-lengths along its two axes
  for (int k = 0; k < 2; ++k) {
    semi[k] = options.box_scale * std::sqrt(std::max(0.0, 3.0 * (eig.eigenvalues()[k] - 1.0 / 12.0)));
    semi[k] = std::max(semi[k], 0.5);
    half += semi[k] * eig.eigenvectors().col(k).cwiseAbs();
  }
  det.half_extent = half + Eigen::Vector2d::Constant(options.box_margin_px);

  const CameraIntrinsics& k = image.intrinsics;
  const double z_surface = RobustDepth(image.depth, k.depth_scale_m, blob.pixels, options.edge_m);
  if (z_surface > 0.0) {
    det.has_depth = true;
    // The smaller half-length spans the branch: its radius in pixels.
    det.radius_m = std::clamp(semi[0] * z_surface / k.fx, 0.002, 0.06);
    const double z_axis = z_surface + options.axis_offset_ratio * det.radius_m;
    det.position = k.Unproject(det.center.x(), det.center.y(), z_axis);
  }
  return det;
}

}  // namespace simtree::tracking::detail
