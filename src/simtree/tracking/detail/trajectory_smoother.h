#pragma once
// Offline smoothing of measured marker positions: a constant-velocity Kalman filter forward and a
// Rauch-Tung-Striebel pass backward over each run of consecutive measured frames, per camera axis.
// A tape's depth, read from a few noisy pixels, scatters by several millimetres from frame to frame
// while the branch moves smoothly at 30 frames per second; the smoother uses the frames on both
// sides of each one. Only measured frames get a position (a gap splits a run and is not filled).

#include "simtree/io/trajectories.h"

namespace simtree::tracking::detail {

struct SmootherOptions {
  double process_noise_mps2 = 8.0;  // white acceleration (m/s^2)
  double noise_xy_m = 0.002;        // measurement noise across the viewing ray (m)
  double noise_z_m = 0.008;         // along it (m)
};

// Smooths every track of `trajectories` in place.
void SmoothTrajectories(Trajectories& trajectories, const SmootherOptions& options);

}  // namespace simtree::tracking::detail
