#pragma once
// Small synthetic scenes in a camera frame (OpenCV: x right, y down, z forward) for the scan and
// registration tests: a ground plane below a level camera and an upright trunk, seen from one
// side, with seeded noise.

#include <cmath>
#include <numbers>
#include <random>

#include <open3d/geometry/PointCloud.h>

namespace simtree::test {

// Ground: the plane y = camera_height (1.2 m below the camera), x in [-1.5, 1.5], z in [1, 4].
inline void AddGround(open3d::geometry::PointCloud& cloud, double spacing, double noise,
                      uint64_t seed, double camera_height = 1.2) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  for (double x = -1.5; x <= 1.5; x += spacing) {
    for (double z = 1.0; z <= 4.0; z += spacing) {
      cloud.points_.emplace_back(x, camera_height + gauss(rng), z);
    }
  }
}

// The camera's half of an upright cylinder (axis parallel to -y) of `radius` at (x0, z0), from
// the ground (y = 1.2) up to y = 1.2 - height.
inline void AddTrunk(open3d::geometry::PointCloud& cloud, double x0, double z0, double radius,
                     double height, double spacing, double noise, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  const double step = spacing / radius;
  for (double y = 1.2; y >= 1.2 - height; y -= spacing) {
    // Angles facing the camera (at the origin): around the direction back to the camera.
    const double facing = std::atan2(-x0, -z0);
    for (double a = facing - 1.4; a <= facing + 1.4; a += step) {
      const double r = radius + gauss(rng);
      cloud.points_.emplace_back(x0 + r * std::sin(a), y, z0 + r * std::cos(a));
    }
  }
}

}  // namespace simtree::test
