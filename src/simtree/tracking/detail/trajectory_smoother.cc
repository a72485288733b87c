#include "simtree/tracking/detail/trajectory_smoother.h"

#include <vector>

#include <Eigen/Dense>

namespace simtree::tracking::detail {
namespace {

// Smooths one axis of one run: `z` measurements at times `t`, noise `r` (m), process noise `q`.
void SmoothRun(const std::vector<double>& t, std::vector<double>& z, double r, double q) {
  const size_t n = z.size();
  if (n < 3) return;
  std::vector<Eigen::Vector2d> xf(n), xp(n);
  std::vector<Eigen::Matrix2d> pf(n), pp(n), f(n);
  xf[0] = Eigen::Vector2d(z[0], 0.0);
  pf[0] << r * r, 0.0, 0.0, 1.0;
  for (size_t k = 1; k < n; ++k) {
    const double dt = t[k] - t[k - 1];
    f[k] << 1.0, dt, 0.0, 1.0;
    Eigen::Matrix2d qm;
    qm << dt * dt * dt * dt / 4.0, dt * dt * dt / 2.0, dt * dt * dt / 2.0, dt * dt;
    xp[k] = f[k] * xf[k - 1];
    pp[k] = f[k] * pf[k - 1] * f[k].transpose() + q * q * qm;
    const double s = pp[k](0, 0) + r * r;
    const Eigen::Vector2d gain = pp[k].col(0) / s;
    xf[k] = xp[k] + gain * (z[k] - xp[k][0]);
    pf[k] = (Eigen::Matrix2d::Identity() - gain * Eigen::RowVector2d(1.0, 0.0)) * pp[k];
  }
  Eigen::Vector2d xs = xf[n - 1];
  Eigen::Matrix2d ps = pf[n - 1];
  z[n - 1] = xs[0];
  for (size_t k = n - 1; k-- > 0;) {
    const Eigen::Matrix2d c = pf[k] * f[k + 1].transpose() * pp[k + 1].inverse();
    xs = xf[k] + c * (xs - xp[k + 1]);
    ps = pf[k] + c * (ps - pp[k + 1]) * c.transpose();
    z[k] = xs[0];
  }
}

}  // namespace

void SmoothTrajectories(Trajectories& trajectories, const SmootherOptions& options) {
  const int frames = trajectories.frame_count();
  for (MarkerTrack& track : trajectories.tracks) {
    int start = 0;
    while (start < frames) {
      if (!track.valid[start]) {
        ++start;
        continue;
      }
      // A run: consecutive frame numbers, all measured.
      int end = start + 1;
      while (end < frames && track.valid[end] &&
             trajectories.frames[end] == trajectories.frames[end - 1] + 1) {
        ++end;
      }
      std::vector<double> t(trajectories.times_s.begin() + start,
                            trajectories.times_s.begin() + end);
      for (int axis = 0; axis < 3; ++axis) {
        std::vector<double> z;
        for (int k = start; k < end; ++k) z.push_back(track.positions[k][axis]);
        SmoothRun(t, z, axis == 2 ? options.noise_z_m : options.noise_xy_m,
                  options.process_noise_mps2);
        for (int k = start; k < end; ++k) track.positions[k][axis] = z[k - start];
      }
      start = end;
    }
  }
}

}  // namespace simtree::tracking::detail
