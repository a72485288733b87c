#include "simtree/tracking/tracker_error.h"

#include <cmath>
#include <limits>
#include <map>
#include <random>

#include <fmt/format.h>

#include "simtree/core/error.h"

namespace simtree::tracking {
namespace {

void CheckOptions(const TrackerErrorOptions& o) {
  auto in_range = [](double value, double lo, double hi, const char* field) {
    if (!std::isfinite(value) || value < lo || value > hi) {
      throw InputError("tracker error", field,
                       fmt::format("expected a number in [{}, {}], got {}", lo, hi, value));
    }
  };
  in_range(o.rms_error_mm, 0.0, 1000.0, "rms_error_mm");
  in_range(o.depth_ratio, 0.0, 100.0, "depth_ratio");
  in_range(o.correlation, 0.0, 0.999, "correlation");
  in_range(o.gap_start_rate, 0.0, 1.0, "gap_start_rate");
  in_range(o.mean_gap_frames, 1.0, 1e6, "mean_gap_frames");
  in_range(o.jump_rate, 0.0, 1.0, "jump_rate");
  in_range(o.jump_mm, 0.0, 1e4, "jump_mm");
}

}  // namespace

Trajectories SimulateTrackerError(const Trajectories& truth, const TrackerErrorOptions& options,
                                  const std::vector<MarkerFrame2d>* visibility) {
  CheckOptions(options);
  const int frames = truth.frame_count();
  if (visibility != nullptr && static_cast<int>(visibility->size()) != frames) {
    throw InputError("markers_2d", "frames",
                     fmt::format("expected {} frames (as the trajectories), got {}", frames,
                                 visibility->size()));
  }
  // sigma_xy^2 (2 + depth_ratio^2) = rms^2.
  const double sigma_xy =
      1e-3 * options.rms_error_mm / std::sqrt(2.0 + options.depth_ratio * options.depth_ratio);
  const Eigen::Vector3d sigma(sigma_xy, sigma_xy, options.depth_ratio * sigma_xy);
  // AR(1) e_t = c e_{t-1} + sqrt(1 - c^2) n_t keeps the stationary standard deviation.
  const double c = options.correlation;
  const double innovation = std::sqrt(1.0 - c * c);
  const double gap_end_rate = 1.0 / options.mean_gap_frames;

  Trajectories out;
  out.frames = truth.frames;
  out.times_s = truth.times_s;
  out.tracks.reserve(truth.tracks.size());
  for (size_t m = 0; m < truth.tracks.size(); ++m) {
    const MarkerTrack& in = truth.tracks[m];
    // One stream per marker, so adding a marker does not change the others' errors.
    std::mt19937_64 rng(options.seed * 0x9E3779B97F4A7C15ull + static_cast<uint64_t>(in.marker));
    std::normal_distribution<double> normal(0.0, 1.0);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    auto gaussian3 = [&] { return Eigen::Vector3d(normal(rng), normal(rng), normal(rng)); };

    MarkerTrack track;
    track.marker = in.marker;
    track.positions.resize(frames);
    track.valid.resize(frames);
    Eigen::Vector3d error = sigma.cwiseProduct(gaussian3());
    bool lost = false;
    for (int f = 0; f < frames; ++f) {
      error = c * error + innovation * sigma.cwiseProduct(gaussian3());
      lost = lost ? uniform(rng) >= gap_end_rate : uniform(rng) < options.gap_start_rate;
      const bool jump = uniform(rng) < options.jump_rate;
      Eigen::Vector3d direction = gaussian3();
      direction.normalize();

      bool seen = in.valid[f] && !lost;
      if (seen && visibility != nullptr) {
        for (const MarkerBox2d& box : (*visibility)[f].markers) {
          if (box.id == in.marker) seen = box.visible;
        }
      }
      track.valid[f] = seen;
      if (!seen) {
        track.positions[f] = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      track.positions[f] = in.positions[f] + error;
      if (jump) track.positions[f] += 1e-3 * options.jump_mm * direction;
    }
    out.tracks.push_back(std::move(track));
  }
  return out;
}

}  // namespace simtree::tracking
