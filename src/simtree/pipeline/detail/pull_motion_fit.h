#pragma once
// The pull's second step: the rope points the static fit ranks best are each simulated, and the
// one whose simulated markers follow the tracked motion best wins, with its force's size and its
// release time fitted to that motion (the direction stays the static fit's). The static fit sees
// only the held pose; the motion after the release also carries where the rope was, how hard it
// pulled and, to a fraction of a frame, when it let go (a release detected from speeds lags the
// true one by a frame or two, and at 1.3 Hz one frame is 16 degrees of phase).

#include <vector>

#include <Eigen/Geometry>

#include "simtree/core/tree.h"
#include "simtree/io/trajectories.h"

namespace simtree::pipeline::detail {

// A tracked marker the fit uses: where it sits on the tree, its track and its rest position.
struct PullObservation {
  int branch = 0;
  double arc_length = 0.0;
  Eigen::Vector3d held = Eigen::Vector3d::Zero();  // mean held displacement (world, m)
  const MarkerTrack* track = nullptr;
  Eigen::Vector3d rest_camera = Eigen::Vector3d::Zero();  // mean rest position (camera, m)
};

// A rope point and the force the static fit gives it.
struct PullCandidate {
  int branch = 0;
  double arc_length = 0.0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // N, world
  double static_residual_m = 0.0;                   // norm over all held displacements
};

struct MotionFitOptions {
  double window_s = 3.0;              // s of motion after the release fitted (> 0)
  double max_release_shift_s = 0.15;  // s the release may move from the detected one (>= 0)
  // A marker whose residual, as a share of its own motion, exceeds this many times the median
  // marker's share and `outlier_share` is left out and the fit redone once (a track that
  // swapped or slipped).
  double outlier_factor = 3.0;  // > 1
  double outlier_share = 0.2;   // > 0
};

struct MotionFit {
  bool fitted = false;
  PullCandidate candidate;      // the winner, its force refitted on the motion
  double release_s = 0.0;       // fitted release: a step boundary of the replay
  double time_step_s = 0.0;     // the step the fit simulated with: the replay's
  double residual_rms_m = 0.0;  // per sample, of the fitted displacements
  double observed_rms_m = 0.0;  // per sample, of the tracked displacements themselves
  int markers = 0;              // markers the final fit used
  int samples = 0;              // marker-frames the final fit used
};

// `candidates`: best first; the tracked samples from `hold_s` (the hold's start) to `release_s`
// (as detected) + `window_s` are fitted; a force over `max_force_n` is refused. Returns
// fitted = false when no candidate gives an acceptable force.
MotionFit FitPullOnMotion(const Tree& tree, const Trajectories& tracks,
                          const Eigen::Isometry3d& world_from_camera,
                          const std::vector<PullObservation>& observations,
                          const std::vector<PullCandidate>& candidates, double hold_s,
                          double release_s, double max_force_n, const MotionFitOptions& options);

}  // namespace simtree::pipeline::detail
