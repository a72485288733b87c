#include "simtree/tracking/detail/motion_model.h"

#include <cmath>

namespace simtree::tracking::detail {
namespace {

constexpr double kInitialVelocitySigma = 0.5;  // m/s

}  // namespace

MarkerMotionModel::MarkerMotionModel(const MotionModelParams& params,
                                     const Eigen::Vector3d& position)
    : params_(params), rest_(position) {
  for (int i = 0; i < 3; ++i) {
    const double r = i == 2 ? params.noise_z_m : params.noise_xy_m;
    axes_[i].x = Eigen::Vector2d(position[i], 0.0);
    axes_[i].p = Eigen::Matrix2d::Zero();
    axes_[i].p(0, 0) = r * r;
    axes_[i].p(1, 1) = kInitialVelocitySigma * kInitialVelocitySigma;
  }
}

MarkerMotionModel::MarkerMotionModel(const MotionModelParams& params,
                                     const Eigen::Vector3d& position, const Eigen::Vector3d& rest)
    : MarkerMotionModel(params, position) {
  rest_ = rest;
}

void MarkerMotionModel::Predict(double dt) {
  Eigen::Matrix2d f;
  if (params_.kind == MotionModelKind::kDampedOscillator) {
    // Semi-implicit Euler on x'' = -w^2 (x - rest) - 2 zeta w x'.
    const double w = 2.0 * M_PI * params_.oscillator_frequency_hz;
    const double a = -w * w * dt;
    const double b = 1.0 - 2.0 * params_.oscillator_damping * w * dt;
    f << 1.0 + a * dt, b * dt, a, b;
  } else {
    f << 1.0, dt, 0.0, 1.0;
  }
  const double q = params_.process_noise_mps2 * params_.process_noise_mps2;
  Eigen::Matrix2d qm;
  qm << dt * dt * dt * dt / 4.0, dt * dt * dt / 2.0, dt * dt * dt / 2.0, dt * dt;
  for (int i = 0; i < 3; ++i) {
    Axis& axis = axes_[i];
    Eigen::Vector2d offset = axis.x;
    if (params_.kind == MotionModelKind::kDampedOscillator) offset[0] -= rest_[i];
    offset = f * offset;
    if (params_.kind == MotionModelKind::kDampedOscillator) offset[0] += rest_[i];
    axis.x = offset;
    axis.p = f * axis.p * f.transpose() + q * qm;
  }
}

void MarkerMotionModel::Update(const Eigen::Vector3d& measured) {
  for (int i = 0; i < 3; ++i) {
    Axis& axis = axes_[i];
    const double r = i == 2 ? params_.noise_z_m : params_.noise_xy_m;
    const double s = axis.p(0, 0) + r * r;
    const Eigen::Vector2d k = axis.p.col(0) / s;
    axis.x += k * (measured[i] - axis.x[0]);
    const Eigen::Matrix2d ikh = Eigen::Matrix2d::Identity() - k * Eigen::RowVector2d(1.0, 0.0);
    axis.p = ikh * axis.p;
    axis.p = 0.5 * (axis.p + axis.p.transpose()).eval();
  }
}

void MarkerMotionModel::ResetVelocity() {
  for (Axis& axis : axes_) {
    axis.x[1] = 0.0;
    axis.p(0, 1) = axis.p(1, 0) = 0.0;
    axis.p(1, 1) = kInitialVelocitySigma * kInitialVelocitySigma;
  }
}

void MarkerMotionModel::ScaleVelocity(double factor) {
  for (Axis& axis : axes_) axis.x[1] *= factor;
}

Eigen::Vector3d MarkerMotionModel::position() const {
  return {axes_[0].x[0], axes_[1].x[0], axes_[2].x[0]};
}

Eigen::Vector3d MarkerMotionModel::velocity() const {
  return {axes_[0].x[1], axes_[1].x[1], axes_[2].x[1]};
}

Eigen::Vector3d MarkerMotionModel::position_sigma() const {
  return {std::sqrt(axes_[0].p(0, 0)), std::sqrt(axes_[1].p(0, 0)), std::sqrt(axes_[2].p(0, 0))};
}

}  // namespace simtree::tracking::detail
