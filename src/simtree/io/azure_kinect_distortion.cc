// The Azure Kinect SDK's Brown-Conrady lens model: projection, and its inverse by Newton's method.

#include <cmath>
#include <optional>

#include <Eigen/Dense>

#include "simtree/io/azure_kinect.h"

namespace simtree {
namespace {

constexpr int kNewtonIterations = 20;
constexpr double kNewtonTolerance = 1e-20;  // squared normalized residual: ~1e-7 pixels
constexpr double kJacobianStep = 1e-7;

bool WithinRadius(const BrownConradyCamera& c, const Eigen::Vector2d& xy) {
  if (c.metric_radius <= 0) return true;
  const double dx = xy.x() - c.codx;
  const double dy = xy.y() - c.cody;
  return dx * dx + dy * dy <= c.metric_radius * c.metric_radius;
}

}  // namespace

Eigen::Vector2d BrownConradyCamera::Distort(const Eigen::Vector2d& xy) const {
  const double x = xy.x() - codx;
  const double y = xy.y() - cody;
  const double r2 = x * x + y * y;
  const double r4 = r2 * r2;
  const double r6 = r4 * r2;
  const double numerator = 1 + k1 * r2 + k2 * r4 + k3 * r6;
  const double denominator = 1 + k4 * r2 + k5 * r4 + k6 * r6;
  const double d = denominator != 0 ? numerator / denominator : 1.0;
  const double xd = x * d + (r2 + 2 * x * x) * p2 + 2 * x * y * p1;
  const double yd = y * d + (r2 + 2 * y * y) * p1 + 2 * x * y * p2;
  return {xd + codx, yd + cody};
}

std::optional<Eigen::Vector2d> BrownConradyCamera::Undistort(
    const Eigen::Vector2d& distorted) const {
  Eigen::Vector2d xy = distorted;
  for (int i = 0; i < kNewtonIterations; ++i) {
    const Eigen::Vector2d residual = Distort(xy) - distorted;
    if (residual.squaredNorm() < kNewtonTolerance) {
      if (!WithinRadius(*this, xy)) return std::nullopt;
      return xy;
    }
    // The model is smooth and nearly the identity near the centre: a numerical Jacobian is
    // accurate enough and keeps the model in one place (Distort).
    Eigen::Matrix2d jacobian;
    for (int axis = 0; axis < 2; ++axis) {
      Eigen::Vector2d step = Eigen::Vector2d::Zero();
      step[axis] = kJacobianStep;
      jacobian.col(axis) = (Distort(xy + step) - Distort(xy - step)) / (2 * kJacobianStep);
    }
    if (std::abs(jacobian.determinant()) < 1e-9) return std::nullopt;
    xy -= jacobian.inverse() * residual;
    if (!xy.allFinite()) return std::nullopt;
  }
  return std::nullopt;
}

std::optional<Eigen::Vector2d> BrownConradyCamera::Project(const Eigen::Vector3d& point) const {
  if (!(point.z() > 0)) return std::nullopt;
  const Eigen::Vector2d xy(point.x() / point.z(), point.y() / point.z());
  if (!WithinRadius(*this, xy)) return std::nullopt;
  const Eigen::Vector2d d = Distort(xy);
  return Eigen::Vector2d(fx * d.x() + cx, fy * d.y() + cy);
}

std::optional<Eigen::Vector2d> BrownConradyCamera::PixelRay(double u, double v) const {
  return Undistort(Eigen::Vector2d((u - cx) / fx, (v - cy) / fy));
}

CameraIntrinsics BrownConradyCamera::Pinhole() const {
  CameraIntrinsics k;
  k.width = width;
  k.height = height;
  k.fx = fx;
  k.fy = fy;
  k.cx = cx;
  k.cy = cy;
  k.depth_scale_m = 0.001;
  return k;
}

}  // namespace simtree
