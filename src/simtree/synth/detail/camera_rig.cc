#include "simtree/synth/detail/camera_rig.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "simtree/core/error.h"

namespace simtree::synth {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

double TreeHeight(const Tree& tree) {
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  return std::max(0.1, hi.z());
}

// Where a person aims: the middle of the crown's footprint, at half the tree's height.
Eigen::Vector3d AimPoint(const Tree& tree) {
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  return {0.5 * (lo.x() + hi.x()), 0.5 * (lo.y() + hi.y()), 0.5 * std::max(0.1, hi.z())};
}

// The distance at which a tree of `height` fits a vertical field of view, aimed at mid-height.
double FitDistance(double height, double vertical_fov_deg, double margin) {
  return margin * 0.5 * height / std::tan(0.5 * vertical_fov_deg * kDegree);
}

}  // namespace

Eigen::Isometry3d LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                         const Eigen::Vector3d& up, double roll) {
  const Eigen::Vector3d forward = target - eye;
  if (!(forward.norm() > 1e-9) || !eye.allFinite() || !target.allFinite()) {
    throw InputError("camera", "look_at", "expected a camera position apart from its target");
  }
  const Eigen::Vector3d z = forward.normalized();
  Eigen::Vector3d x = z.cross(up);
  if (x.norm() < 1e-6) {
    throw InputError("camera", "look_at", "the camera looks straight along the up direction");
  }
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d rotation;
  rotation << x, y, z;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() = eye;
  return pose;
}

ScanRigOptions ScanRigOptions::Hard() {
  ScanRigOptions options;
  options.views = 7;
  options.azimuth_jitter_deg = 14.0;
  options.distance_jitter_m = 0.3;
  options.aim_jitter_deg = 5.0;
  options.roll_jitter_deg = 4.0;
  return options;
}

std::vector<Eigen::Isometry3d> ScanViewPoses(const Tree& tree, const ScanRigOptions& options,
                                             uint64_t seed) {
  if (options.views < 1) {
    throw InputError("scan rig", "views", "expected at least one view");
  }
  if (!(options.min_distance_m > 0 && options.max_distance_m >= options.min_distance_m)) {
    throw InputError("scan rig", "distance", "expected 0 < min_distance_m <= max_distance_m");
  }
  std::mt19937_64 rng(seed);
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  const double height = TreeHeight(tree);
  const double base_distance =
      std::clamp(FitDistance(height, options.vertical_fov_deg, options.fit_margin),
                 options.min_distance_m, options.max_distance_m);
  const double step = options.step_deg > 0 ? options.step_deg : 360.0 / options.views;
  const double start = uniform(0.0, 360.0);
  const Eigen::Vector3d aim_centre = AimPoint(tree);

  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(options.views);
  for (int i = 0; i < options.views; ++i) {
    const double azimuth =
        (start + i * step + uniform(-1.0, 1.0) * options.azimuth_jitter_deg) * kDegree;
    const double distance =
        std::clamp(base_distance + uniform(-1.0, 1.0) * options.distance_jitter_m,
                   options.min_distance_m, options.max_distance_m);
    const double camera_height = uniform(options.min_height_m, options.max_height_m);
    const Eigen::Vector3d eye(distance * std::cos(azimuth), distance * std::sin(azimuth),
                              camera_height);
    // Aim off the centre by a small angle in a random direction across the view.
    const double off = uniform(0.0, options.aim_jitter_deg) * kDegree * distance;
    const double off_angle = uniform(0.0, 2.0 * std::numbers::pi);
    const Eigen::Vector3d across(-std::sin(azimuth), std::cos(azimuth), 0.0);
    const Eigen::Vector3d target =
        aim_centre +
        off * (std::cos(off_angle) * across + std::sin(off_angle) * Eigen::Vector3d::UnitZ());
    const double roll = uniform(-1.0, 1.0) * options.roll_jitter_deg * kDegree;
    poses.push_back(LookAt(eye, target, Eigen::Vector3d::UnitZ(), roll));
  }
  return poses;
}

Eigen::Isometry3d PullCameraPose(const Tree& tree, const Eigen::Vector3d& pull_direction,
                                 const PullCameraOptions& options) {
  Eigen::Vector3d horizontal(pull_direction.x(), pull_direction.y(), 0.0);
  if (horizontal.norm() < 1e-9) horizontal = Eigen::Vector3d::UnitX();
  horizontal.normalize();
  const double height = TreeHeight(tree);
  const double distance = options.distance_m > 0
                              ? options.distance_m
                              : std::clamp(FitDistance(height, 65.0, 1.1), 1.8, 3.2);
  const Eigen::Vector3d side =
      Eigen::AngleAxisd(options.side_angle_deg * kDegree, Eigen::Vector3d::UnitZ()) * horizontal;
  const Eigen::Vector3d eye = distance * side + Eigen::Vector3d(0, 0, options.height_m);
  return LookAt(eye, AimPoint(tree));
}

}  // namespace simtree::synth
