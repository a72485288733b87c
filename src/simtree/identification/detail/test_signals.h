#pragma once
// Synthetic free-decay records with known modes, for tests, benchmarks and the documentation's
// measurements: sums of damped sinusoids, white measurement noise and tracker-like gaps.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "simtree/identification/detail/sampled_signal.h"
#include "simtree/io/capture.h"
#include "simtree/io/trajectories.h"

namespace simtree::identification {

// x(t) = amplitude e^(-zeta 2 pi f t) cos(2 pi f sqrt(1 - zeta^2) t + phase): a mode with natural
// frequency f and damping ratio zeta, released at t = 0.
struct DampedSinusoid {
  double frequency_hz = 1.0;
  double damping_ratio = 0.03;
  double amplitude = 1.0;
  double phase_rad = 0.0;

  double operator()(double t) const;
};

struct DecayRecordOptions {
  double fps = 30.0;         // samples per second
  double duration_s = 10.0;  // s
  double noise_std = 0.0;    // white Gaussian, signal units
  double offset = 0.0;       // constant added to every channel, signal units
  // Gaps: at each valid sample a gap starts with this probability and lasts 1..max_gap_samples.
  double gap_rate = 0.0;
  int max_gap_samples = 5;
  uint64_t seed = 1;  // of the noise and the gaps

  // Throws InputError naming the field for a value out of range.
  void Validate() const;
};

// One channel per entry of `channels`, each the sum of its modes, sampled from t = 0.
SampledSignal MakeDecayRecord(const std::vector<std::vector<DampedSinusoid>>& channels,
                              const DecayRecordOptions& options);

// A small marker tree with known link deflections, for end-to-end tests of deflection signals and
// identification: a root marker (its displacement given per camera axis), and links, each a rest
// direction and length from its parent marker with theta_u(t), theta_w(t) against its parent link
// in the frame deflection.h defines. Before `hold_s` the tree is held at its t = 0 pose (pulled);
// the decay starts at the release, t = hold_s.
struct SyntheticLink {
  int parent = -1;  // index into `links`, -1: the link starts at the root marker
  Eigen::Vector3d rest_direction = -Eigen::Vector3d::UnitY();  // camera frame
  double length_m = 0.5;
  std::vector<DampedSinusoid> theta_u, theta_w;  // radians
};
struct SyntheticMarkerTree {
  Eigen::Vector3d root_position = Eigen::Vector3d(0.0, 0.3, 2.5);  // camera frame, m
  std::vector<DampedSinusoid> root_motion[3];                      // per camera axis, m
  std::vector<SyntheticLink> links;
  Eigen::Vector3d camera_up = -Eigen::Vector3d::UnitY();
};
// Marker 0 is the root; link k ends at marker k + 1. `markers` receives the marker list.
Trajectories MakeMarkerTrajectories(const SyntheticMarkerTree& tree, double fps, double hold_s,
                                    double decay_s, std::vector<MarkerLink>* markers);

// A marker tree whose links ring on their own, the paper's per-branch model (Fig. 8): each link's
// two bending planes at frequencies a few percent apart with one damping ratio, drawn inside the
// paper's Table IV ranges; each child link rides on its parent's rotation (link k > 0 hangs from
// link (k - 1) / 2); the root marker moves along two camera axes at two frequencies of its own.
// No two links share a mode: the opposite of a whole-tree FEM record, where every link reads the
// same global modes.
struct IndependentTreeOptions {
  int links = 6;  // besides the root marker's displacement
  double min_frequency_hz = 0.72, max_frequency_hz = 1.50;
  double min_damping = 0.022, max_damping = 0.060;
  double min_plane_split = 0.03, max_plane_split = 0.08;  // relative, between the two planes
  double min_angle_rad = 0.06, max_angle_rad = 0.15;      // the stronger plane's amplitude
  double root_amplitude_m = 0.012;                        // the root's stronger axis
  uint64_t seed = 1;

  // Throws InputError naming the field for a value out of range.
  void Validate() const;
};
// `truth` receives, per marker (0: the root's displacement, k + 1: link k), the mode a record of
// `record_s` would call dominant (the larger amplitude times the integral of its envelope).
SyntheticMarkerTree MakeIndependentModeTree(const IndependentTreeOptions& options, double record_s,
                                            std::vector<DampedSinusoid>* truth);

}  // namespace simtree::identification
