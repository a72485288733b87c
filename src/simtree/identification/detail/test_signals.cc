#include "simtree/identification/detail/test_signals.h"

#include <cmath>
#include <limits>
#include <random>

#include <fmt/format.h>

#include <Eigen/Geometry>

#include "simtree/core/frames.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/units.h"

namespace simtree::identification {

double DampedSinusoid::operator()(double t) const {
  const double omega = kTwoPi * frequency_hz;
  const double damped = omega * std::sqrt(std::max(0.0, 1 - damping_ratio * damping_ratio));
  return amplitude * std::exp(-damping_ratio * omega * t) * std::cos(damped * t + phase_rad);
}

void DecayRecordOptions::Validate() const {
  CheckPositive("fps", fps);
  CheckPositive("duration_s", duration_s);
  CheckNonNegative("noise_std", noise_std);
  CheckThat(std::isfinite(offset), "offset", "a finite number", offset);
  CheckShare("gap_rate", gap_rate);
  CheckAtLeast("max_gap_samples", max_gap_samples, 1);
}

SampledSignal MakeDecayRecord(const std::vector<std::vector<DampedSinusoid>>& channels,
                              const DecayRecordOptions& options) {
  options.Validate();
  std::mt19937_64 rng(options.seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::uniform_int_distribution<int> gap_length(1, options.max_gap_samples);
  const int n = static_cast<int>(std::lround(options.duration_s * options.fps));
  SampledSignal out;
  out.dt = 1.0 / options.fps;
  out.values.resize(n, static_cast<int>(channels.size()));
  out.valid.assign(n, true);
  for (int c = 0; c < static_cast<int>(channels.size()); ++c) {
    out.channel_names.push_back(fmt::format("c{}", c));
  }
  for (int i = 0; i < n; ++i) {
    const double t = i * out.dt;
    for (int c = 0; c < static_cast<int>(channels.size()); ++c) {
      double x = options.offset;
      for (const DampedSinusoid& mode : channels[c]) x += mode(t);
      out.values(i, c) = x + options.noise_std * noise(rng);
    }
  }
  if (options.gap_rate > 0) {
    for (int i = 0; i < n; ++i) {
      if (!out.valid[i] || uniform(rng) >= options.gap_rate) continue;
      const int length = gap_length(rng);
      for (int k = i; k < std::min(n, i + length); ++k) {
        out.valid[k] = false;
        out.values.row(k).setConstant(std::numeric_limits<double>::quiet_NaN());
      }
      i += length;
    }
  }
  return out;
}

Trajectories MakeMarkerTrajectories(const SyntheticMarkerTree& tree, double fps, double hold_s,
                                    double decay_s, std::vector<MarkerLink>* markers) {
  const int count = static_cast<int>(tree.links.size()) + 1;
  Trajectories out;
  for (int m = 0; m < count; ++m) out.tracks.push_back(MarkerTrack{m, {}, {}});
  if (markers) {
    markers->clear();
    markers->push_back(MarkerLink{0, "M0", -1, std::nullopt});
    for (int k = 0; k < count - 1; ++k) {
      const int parent = tree.links[k].parent < 0 ? 0 : tree.links[k].parent + 1;
      markers->push_back(MarkerLink{k + 1, fmt::format("M{}", k + 1), parent, std::nullopt});
    }
  }
  // Rest directions and frames of every link, as deflection.h defines them.
  std::vector<Frame> frames;
  for (const SyntheticLink& link : tree.links) {
    const Eigen::Vector3d parent_axis =
        link.parent < 0 ? tree.camera_up : tree.links[link.parent].rest_direction.normalized();
    frames.push_back(
        FrameFromAxes(link.rest_direction.normalized(), parent_axis, Eigen::Vector3d::UnitX()));
  }
  const int frames_total = static_cast<int>(std::lround((hold_s + decay_s) * fps));
  for (int i = 0; i < frames_total; ++i) {
    const double time = i / fps;
    const double t = std::max(0.0, time - hold_s);
    std::vector<Eigen::Vector3d> position(count);
    std::vector<Eigen::Vector3d> direction(tree.links.size());
    position[0] = tree.root_position;
    for (int a = 0; a < 3; ++a) {
      for (const DampedSinusoid& mode : tree.root_motion[a]) position[0][a] += mode(t);
    }
    for (size_t k = 0; k < tree.links.size(); ++k) {
      const SyntheticLink& link = tree.links[k];
      double tu = 0, tw = 0;
      for (const DampedSinusoid& mode : link.theta_u) tu += mode(t);
      for (const DampedSinusoid& mode : link.theta_w) tw += mode(t);
      Eigen::Vector3d d =
          (frames[k].v + std::tan(tu) * frames[k].u + std::tan(tw) * frames[k].w).normalized();
      Eigen::Vector3d base = position[0];
      if (link.parent >= 0) {
        // Carried by the parent link's swing (the shortest rotation from its rest direction).
        const Eigen::Vector3d parent_rest = tree.links[link.parent].rest_direction.normalized();
        d = Eigen::Quaterniond::FromTwoVectors(parent_rest, direction[link.parent]) * d;
        base = position[link.parent + 1];
      }
      direction[k] = d;
      position[k + 1] = base + link.length_m * d;
    }
    out.AddFrame(i, time, position, std::vector<bool>(count, true));
  }
  return out;
}

}  // namespace simtree::identification
