#include "simtree/identification/release.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "simtree/core/statistics.h"

namespace simtree {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct MarkerMotion {
  std::vector<double> speed;  // speed[i]: over the `lag` frames before frame i (NaN when unknown)
  std::vector<double> sustained;  // SustainedSpeed(speed)
  double noise_speed = 0.0;       // the rms speed noise alone gives
  double peak_speed = 0.0;
};

// The least of each frame's speed and its neighbours' (at least two of the three known): a swing
// keeps its speed for several frames, while a tracker jump the outlier test missed makes two
// lone spikes (into the wrong position and out of it), which must not set the peak or the swing.
std::vector<double> SustainedSpeed(const std::vector<double>& speed) {
  const int n = static_cast<int>(speed.size());
  std::vector<double> out(n, kNaN);
  for (int i = 0; i < n; ++i) {
    double least = std::numeric_limits<double>::infinity();
    int known = 0;
    for (int j = std::max(0, i - 1); j <= std::min(n - 1, i + 1); ++j) {
      if (std::isnan(speed[j])) continue;
      least = std::min(least, speed[j]);
      ++known;
    }
    if (known >= 2) out[i] = least;
  }
  return out;
}

// Speeds over a lag of about 0.1 s: at 30 fps a frame-to-frame difference of 2-3 mm tracker noise
// is already 0.1-0.2 m/s, as fast as a gentle swing.
MarkerMotion Motion(const Trajectories& t, const MarkerTrack& track) {
  MarkerMotion m;
  const int n = t.frame_count();
  const double dt = (t.times_s.back() - t.times_s.front()) / (n - 1);
  const int lag = std::max(1, static_cast<int>(std::lround(0.1 / dt)));
  m.speed.assign(n, kNaN);
  for (int i = lag; i < n; ++i) {
    if (!track.valid[i] || !track.valid[i - lag]) continue;
    m.speed[i] = (track.positions[i] - track.positions[i - lag]).norm() /
                 (t.times_s[i] - t.times_s[i - lag]);
  }
  // Noise per axis from second differences (robust to the smooth motion); a difference of two
  // noisy positions over `lag` frames has rms sqrt(2 * 3) sigma in 3D.
  std::vector<double> d2;
  for (int i = 1; i + 1 < n; ++i) {
    if (!track.valid[i - 1] || !track.valid[i] || !track.valid[i + 1]) continue;
    const Eigen::Vector3d d =
        track.positions[i + 1] - 2 * track.positions[i] + track.positions[i - 1];
    for (int k = 0; k < 3; ++k) d2.push_back(std::abs(d[k]));
  }
  const double sigma = d2.empty() ? 0.0 : UpperMedian(std::move(d2)) / 0.6745 / std::sqrt(6.0);
  m.noise_speed = sigma * std::sqrt(6.0) / (lag * dt);
  m.sustained = SustainedSpeed(m.speed);
  for (int i = 0; i < n; ++i) {
    if (!std::isnan(m.sustained[i])) m.peak_speed = std::max(m.peak_speed, m.sustained[i]);
  }
  return m;
}

}  // namespace

int FrameAtOrAfter(const Trajectories& t, double time_s) {
  const auto it = std::lower_bound(t.times_s.begin(), t.times_s.end(), time_s - 1e-9);
  return static_cast<int>(it - t.times_s.begin());
}

ReleaseDetection DetectRelease(const Trajectories& t, const ReleaseOptions& options) {
  ReleaseDetection out;
  out.time_s = t.times_s.empty() ? 0.0 : t.times_s.front();
  if (t.frame_count() < 3 || t.tracks.empty()) {
    out.note = "too few frames to look for a release; the record is taken from its first frame";
    return out;
  }
  // The marker that moves most above its own noise decides.
  MarkerMotion best;
  double best_ratio = -1;
  for (const MarkerTrack& track : t.tracks) {
    MarkerMotion m = Motion(t, track);
    const double ratio = m.peak_speed / std::max(m.noise_speed, 1e-12);
    if (ratio > best_ratio) {
      best_ratio = ratio;
      best = std::move(m);
      out.marker = track.marker;
    }
  }
  out.peak_speed = best.peak_speed;
  out.noise_speed = best.noise_speed;
  if (best.peak_speed <= options.noise_factor * best.noise_speed) {
    out.note = fmt::format(
        "no marker moves above its noise (peak {:.3g} m/s, noise {:.3g} m/s); "
        "the record is taken from its first frame",
        best.peak_speed, best.noise_speed);
    return out;
  }
  const int n = t.frame_count();
  int swing = -1;
  for (int i = 1; i < n && swing < 0; ++i) {
    if (best.sustained[i] >= options.swing_fraction * best.peak_speed) swing = i;
  }
  const double quiet =
      std::max(options.quiet_fraction * best.peak_speed, options.noise_factor * best.noise_speed);
  int release = -1;
  for (int i = swing; i >= 1; --i) {
    if (!std::isnan(best.speed[i]) && best.speed[i] <= quiet) {
      release = i;
      break;
    }
  }
  if (release < 0) {
    out.note = fmt::format(
        "marker {} is already swinging in the first frames; the record is "
        "taken from its first frame",
        out.marker);
    return out;
  }
  out.found = true;
  out.frame_index = release;
  out.time_s = t.times_s[release];
  out.note = fmt::format("marker {} is still until {:.3f} s, then swings (peak {:.3g} m/s)",
                         out.marker, out.time_s, best.peak_speed);
  return out;
}

}  // namespace simtree
