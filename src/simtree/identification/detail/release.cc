#include "simtree/identification/detail/release.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "simtree/core/option_checks.h"
#include "simtree/core/statistics.h"
#include "simtree/core/units.h"

namespace simtree::identification {
namespace {

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

// Where one marker's motion puts the release: its first swing (a speed kept at
// `swing_fraction` of its peak), and walking back from there its last still frame.
struct MarkerRelease {
  int swing = -1;
  int still = -1;
  bool seen_throughout = false;  // every speed from the still frame to the swing is known
};

MarkerRelease ReleaseOf(const MarkerMotion& m, int hold_frames, const ReleaseOptions& options) {
  MarkerRelease r;
  const int n = static_cast<int>(m.speed.size());
  for (int i = 1; i < n && r.swing < 0; ++i) {
    if (m.sustained[i] >= options.swing_fraction * m.peak_speed) r.swing = i;
  }
  const double quiet =
      std::max(options.quiet_fraction * m.peak_speed, options.noise_factor * m.noise_speed);
  // Still through the `hold_frames` up to frame i (half of them known at least): a swing's
  // turning point is slow for a frame or two, a hold for longer.
  const auto held = [&](int i) {
    int known = 0;
    for (int j = std::max(0, i - hold_frames); j <= i; ++j) {
      if (std::isnan(m.speed[j])) continue;
      if (m.speed[j] > quiet) return false;
      ++known;
    }
    return 2 * known > hold_frames;
  };
  bool gap = false;
  for (int i = r.swing; i >= 1; --i) {
    if (std::isnan(m.speed[i])) {
      gap = true;
    } else if (m.speed[i] <= quiet && (i <= hold_frames || held(i))) {
      r.still = i;
      r.seen_throughout = !gap;
      break;
    }
  }
  return r;
}

}  // namespace

void ReleaseOptions::Validate() const {
  CheckThat(swing_fraction > 0 && swing_fraction <= 1, "swing_fraction",
            "a share of the peak speed in (0, 1]", swing_fraction);
  CheckShare("quiet_fraction", quiet_fraction);
  CheckThat(quiet_fraction < swing_fraction, "quiet_fraction",
            fmt::format("< swing_fraction ({})", swing_fraction), quiet_fraction);
  CheckNonNegative("noise_factor", noise_factor);
  CheckNonNegative("min_hold_s", min_hold_s);
}

const char* ToString(ReleaseOutcome outcome) {
  switch (outcome) {
    case ReleaseOutcome::kDetected:
      return "detected";
    case ReleaseOutcome::kGiven:
      return "given";
    case ReleaseOutcome::kTooFewFrames:
      return "too_few_frames";
    case ReleaseOutcome::kNoMotion:
      return "no_motion";
    case ReleaseOutcome::kAlreadySwinging:
      return "already_swinging";
  }
  return "?";
}

int FrameAtOrAfter(const Trajectories& t, double time_s) {
  const auto it = std::lower_bound(t.times_s.begin(), t.times_s.end(), time_s - 1e-9);
  return static_cast<int>(it - t.times_s.begin());
}

ReleaseDetection DetectRelease(const Trajectories& t, const ReleaseOptions& options) {
  options.Validate();
  ReleaseDetection out;
  out.time_s = t.times_s.empty() ? 0.0 : t.times_s.front();
  if (t.frame_count() < 3 || t.tracks.empty()) {
    out.outcome = ReleaseOutcome::kTooFewFrames;
    out.note = "too few frames to look for a release; the record is taken from its first frame";
    return out;
  }
  // The marker that moves most above its own noise decides, unless its tape was lost between
  // the hold and the swing (a still frame before the gap may be the pull's start, not its
  // release): then the next marker, in order of motion over noise, that saw the same swing.
  std::vector<MarkerMotion> motions;
  std::vector<double> ratios;
  for (const MarkerTrack& track : t.tracks) {
    motions.push_back(Motion(t, track));
    ratios.push_back(motions.back().peak_speed / std::max(motions.back().noise_speed, 1e-12));
  }
  std::vector<int> order(motions.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return ratios[a] > ratios[b]; });
  const auto decide = [&](int k) {
    out.marker = t.tracks[k].marker;
    out.peak_speed = motions[k].peak_speed;
    out.noise_speed = motions[k].noise_speed;
  };
  const MarkerMotion& best = motions[order.front()];
  decide(order.front());
  if (best.peak_speed <= options.noise_factor * best.noise_speed) {
    out.outcome = ReleaseOutcome::kNoMotion;
    out.note = fmt::format(
        "no marker moves above its noise (peak {:.3g} m/s, noise {:.3g} m/s); "
        "the record is taken from its first frame",
        best.peak_speed, best.noise_speed);
    return out;
  }
  const double dt = (t.times_s.back() - t.times_s.front()) / (t.frame_count() - 1);
  const int hold_frames = std::max(1, static_cast<int>(std::lround(options.min_hold_s / dt)));
  const MarkerRelease first = ReleaseOf(best, hold_frames, options);
  MarkerRelease release = first;
  if (!first.seen_throughout) {
    const int same_swing = std::max(1, static_cast<int>(std::lround(0.5 / dt)));
    for (size_t o = 1; o < order.size(); ++o) {  // after the best, whose release is `first`
      const int k = order[o];
      const MarkerMotion& m = motions[k];
      if (m.peak_speed <= options.noise_factor * m.noise_speed) break;
      const MarkerRelease r = ReleaseOf(m, hold_frames, options);
      if (r.seen_throughout && r.swing >= 0 && std::abs(r.swing - first.swing) <= same_swing) {
        release = r;
        decide(k);
        break;
      }
    }
  }
  if (release.still < 0) {
    out.outcome = ReleaseOutcome::kAlreadySwinging;
    out.note = fmt::format(
        "marker {} is already swinging in the first frames; the record is "
        "taken from its first frame",
        out.marker);
    return out;
  }
  out.outcome = ReleaseOutcome::kDetected;
  out.frame_index = release.still;
  out.time_s = t.times_s[release.still];
  out.note = fmt::format("marker {} is still until {:.3f} s, then swings (peak {:.3g} m/s){}",
                         out.marker, out.time_s, out.peak_speed,
                         release.seen_throughout ? "" : "; its track has a gap before the swing");
  return out;
}

}  // namespace simtree::identification
