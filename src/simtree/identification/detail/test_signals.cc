#include "simtree/identification/detail/test_signals.h"

#include <cmath>
#include <limits>
#include <random>
#include <utility>

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

void IndependentTreeOptions::Validate() const {
  CheckAtLeast("links", links, 1);
  CheckPositive("min_frequency_hz", min_frequency_hz);
  CheckThat(max_frequency_hz >= min_frequency_hz, "max_frequency_hz", ">= min_frequency_hz",
            max_frequency_hz);
  CheckThat(min_damping > 0 && min_damping < 1, "min_damping", "a damping ratio in (0, 1)",
            min_damping);
  CheckThat(max_damping >= min_damping && max_damping < 1, "max_damping",
            "a damping ratio in [min_damping, 1)", max_damping);
  CheckNonNegative("min_plane_split", min_plane_split);
  CheckThat(max_plane_split >= min_plane_split, "max_plane_split", ">= min_plane_split",
            max_plane_split);
  CheckPositive("min_angle_rad", min_angle_rad);
  CheckThat(max_angle_rad >= min_angle_rad, "max_angle_rad", ">= min_angle_rad", max_angle_rad);
  CheckPositive("root_amplitude_m", root_amplitude_m);
}

namespace {

// What a record `record_s` long shows of a mode: its amplitude times the integral of its envelope.
double PeakWeight(const DampedSinusoid& m, double record_s) {
  const double s = m.damping_ratio * kTwoPi * m.frequency_hz;
  return m.amplitude * (1 - std::exp(-s * record_s)) / s;
}

// Two modes of one damping ratio, `split` apart in frequency, the second weaker by `ratio`; the
// stronger of the two (by PeakWeight) goes to `truth`.
std::pair<DampedSinusoid, DampedSinusoid> PlanePair(std::mt19937_64& rng,
                                                    const IndependentTreeOptions& o,
                                                    double amplitude, double record_s,
                                                    DampedSinusoid* truth) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto in = [&](double lo, double hi) { return lo + (hi - lo) * u(rng); };
  const double zeta = in(o.min_damping, o.max_damping);
  const double f_low = in(o.min_frequency_hz, o.max_frequency_hz / (1 + o.max_plane_split));
  const double f_high = f_low * (1 + in(o.min_plane_split, o.max_plane_split));
  DampedSinusoid a{f_low, zeta, amplitude, in(0, kTwoPi)};
  DampedSinusoid b{f_high, zeta, amplitude * in(0.3, 0.8), in(0, kTwoPi)};
  if (u(rng) < 0.5) std::swap(a.amplitude, b.amplitude);
  *truth = PeakWeight(a, record_s) >= PeakWeight(b, record_s) ? a : b;
  return {a, b};
}

}  // namespace

SyntheticMarkerTree MakeIndependentModeTree(const IndependentTreeOptions& options, double record_s,
                                            std::vector<DampedSinusoid>* truth) {
  options.Validate();
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  SyntheticMarkerTree tree;
  std::vector<DampedSinusoid> dominant(options.links + 1);
  const auto [rx, rz] = PlanePair(rng, options, options.root_amplitude_m, record_s, &dominant[0]);
  tree.root_motion[0] = {rx};
  tree.root_motion[2] = {rz};
  for (int k = 0; k < options.links; ++k) {
    SyntheticLink link;
    link.parent = k == 0 ? -1 : (k - 1) / 2;
    // Up and outwards, each at its own azimuth (camera frame: y down, z away from the camera).
    const double azimuth = kTwoPi * u(rng), lean = 0.3 + 0.6 * u(rng);
    link.rest_direction = Eigen::Vector3d(std::sin(lean) * std::cos(azimuth), -std::cos(lean),
                                          std::sin(lean) * std::sin(azimuth));
    link.length_m = 0.4 + 0.4 * u(rng);
    const double angle =
        options.min_angle_rad + (options.max_angle_rad - options.min_angle_rad) * u(rng);
    const auto [a, b] = PlanePair(rng, options, angle, record_s, &dominant[k + 1]);
    link.theta_u = {a};
    link.theta_w = {b};
    tree.links.push_back(std::move(link));
  }
  if (truth) *truth = std::move(dominant);
  return tree;
}

}  // namespace simtree::identification
