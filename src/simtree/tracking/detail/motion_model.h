#pragma once
// The 3D motion model of one marker: a Kalman filter per camera axis on (position, velocity),
// either constant velocity or a damped oscillator about the marker's rest position.

#include <array>

#include <Eigen/Core>

#include "simtree/tracking/track.h"

namespace simtree::tracking::detail {

struct MotionModelParams {
  MotionModelKind kind = MotionModelKind::kConstantVelocity;
  double process_noise_mps2 = 8.0;       // white acceleration noise (m/s^2)
  double noise_xy_m = 0.002;             // measurement noise across the viewing ray (m)
  double noise_z_m = 0.005;              // along it (m)
  double oscillator_frequency_hz = 1.2;  // the oscillator's natural frequency
  double oscillator_damping = 0.05;      // and damping ratio
};

class MarkerMotionModel {
 public:
  MarkerMotionModel() = default;
  // Starts at `position` (metres, camera frame), at rest, with a wide velocity uncertainty. The
  // rest position of the oscillator is `position`.
  MarkerMotionModel(const MotionModelParams& params, const Eigen::Vector3d& position);
  // The same, with the oscillator's rest position given (a marker found again after a loss).
  MarkerMotionModel(const MotionModelParams& params, const Eigen::Vector3d& position,
                    const Eigen::Vector3d& rest);

  // Moves the state `dt` seconds ahead.
  void Predict(double dt);
  // Corrects the state with a measured position.
  void Update(const Eigen::Vector3d& measured);
  // Forgets the velocity (after a long loss: the marker may come back anywhere near its path).
  void ResetVelocity();
  // Multiplies the velocity by `factor` (a coasting marker's velocity is trusted less and less).
  void ScaleVelocity(double factor);

  Eigen::Vector3d position() const;
  Eigen::Vector3d velocity() const;
  const Eigen::Vector3d& rest() const { return rest_; }
  // Standard deviation of the predicted position per axis (m).
  Eigen::Vector3d position_sigma() const;

 private:
  struct Axis {
    Eigen::Vector2d x = Eigen::Vector2d::Zero();      // position, velocity
    Eigen::Matrix2d p = Eigen::Matrix2d::Identity();  // covariance
  };
  MotionModelParams params_;
  Eigen::Vector3d rest_ = Eigen::Vector3d::Zero();
  std::array<Axis, 3> axes_{};
};

}  // namespace simtree::tracking::detail
