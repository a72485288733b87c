#include "simtree/tracking/detail/band_shape.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

namespace simtree::tracking::detail {
namespace {

// A pixel spans [-0.5, 0.5]^2: its own extent adds 1/12 px^2 to every variance.
constexpr double kPixelVariance = 1.0 / 12.0;

// The blur's variance along a unit direction `d` of the image.
double BlurAlong(const Eigen::Vector2d& blur, const Eigen::Vector2d& d) {
  return blur.x() * d.x() * d.x() + blur.y() * d.y() * d.y();
}

// A uniform interval of variance v has half-length sqrt(3 v); at least half a pixel.
double HalfLength(double variance) {
  return std::max(0.5, std::sqrt(3.0 * std::max(0.0, variance)));
}

}  // namespace

std::array<double, 4> BandShape::Box() const {
  const double hx = half_length * std::abs(axis.x()) + radius * std::abs(axis.y());
  const double hy = half_length * std::abs(axis.y()) + radius * std::abs(axis.x());
  return {center.x() - hx, center.y() - hy, 2.0 * hx, 2.0 * hy};
}

BandShape MeasureBandShape(const std::vector<Eigen::Vector2d>& points,
                           const std::vector<double>& weights,
                           const Eigen::Vector2d& blur_var_px2) {
  double sw = 0.0;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < points.size(); ++i) {
    sw += weights[i];
    mean += weights[i] * points[i];
  }
  mean /= sw;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d d = points[i] - mean;
    cov += weights[i] * d * d.transpose();
  }
  cov /= sw;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  BandShape shape;
  shape.center = mean;
  shape.axis = eig.eigenvectors().col(1);  // the larger eigenvalue: along the branch
  const Eigen::Vector2d across(-shape.axis.y(), shape.axis.x());
  shape.radius =
      HalfLength(eig.eigenvalues()[0] + kPixelVariance - BlurAlong(blur_var_px2, across));
  shape.half_length =
      HalfLength(eig.eigenvalues()[1] + kPixelVariance - BlurAlong(blur_var_px2, shape.axis));
  return shape;
}

}  // namespace simtree::tracking::detail
