#pragma once
// The capture's pull test estimated on the simulation-ready tree, so it can be replayed: a point
// force at one point of one branch. Two steps: the static fit ranks every candidate rope point by
// how well a force there explains the markers' tracked displacements while the rope was held (the
// tree's static response to a unit force along x, y and z, from TreeDynamics::SettleStatic); the
// motion fit (pull_motion_fit.h) simulates the best of them and keeps the one whose markers follow
// the tracked motion through the hold and after the release, with its force and its release time
// fitted to that motion. The hold's start comes from the tracks.

#include <vector>

#include <Eigen/Geometry>

#include "simtree/core/tree.h"
#include "simtree/dynamics/simulate.h"
#include "simtree/io/trajectories.h"
#include "simtree/pipeline/detail/pull_motion_fit.h"

namespace simtree::pipeline::detail {

struct PullFitOptions {
  double rest_s = 0.3;            // s from the record's start averaged for the rest pose (> 0)
  double held_window_s = 0.3;     // s averaged for the held pose, before the release (> 0)
  double release_margin_s = 0.1;  // s before the release left out of the held window (>= 0)
  int arc_samples = 6;            // candidate rope points per branch (>= 1)...
  double min_arc_share = 0.2;     // ... from this share of its length from its base [0, 1) ...
  double max_arc_share = 0.95;    // ... to this share (> min_arc_share, <= 1)
  // A rope point needing more than this to explain the displacements is no pull a person makes
  // (a point near a stiff base explains anything with a huge force).
  double max_force_n = 1000.0;  // N, > 0
  // Nor one whose own point would move more than this many times the largest held displacement
  // of a marker (a thin twig pulled hard, its motion seen by no marker).
  double max_point_displacement_factor = 1.5;  // > 0
  int max_level = 2;                           // deepest branch level a rope is tried on (>= 0)
  double anchor_distance_m = 20.0;  // m: the replayed rope's anchor, along the force (> 0)
  double hold_fraction = 0.95;  // the hold starts when the most-moved marker has this share (0, 1]
  int motion_candidates = 6;    // best static rope points the motion fit simulates (>= 0; 0: none)
  MotionFitOptions motion;

  // Throws InputError ("pull fit options", the field) for a value out of range.
  void Validate() const;
};

struct PullFit {
  int branch = 0;
  double arc_length = 0.0;                          // m from the branch base
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // the rope's point at rest (world)
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // N, world
  double residual_rms_m = 0.0;  // of the markers' held displacements against the static fit
  double observed_rms_m = 0.0;  // of the held displacements themselves
  int markers = 0;              // markers the static fit used
  int candidates = 0;           // rope points tried
  double hold_s = 0.0;
  double release_s = 0.0;  // the replay lets go at its first step starting at or after this
  double detected_release_s = 0.0;  // identification's release, which the motion fit moved
  MotionFit motion;                 // fitted = false: the static fit's point, force and release

  // The schedule that replays it (force mode, anchor far along the force); simulate it with
  // steps of motion.time_step_s when the motion fit ran.
  dynamics::PullSchedule Schedule(double anchor_distance_m = 20.0) const;
};

// `tree`: simulation-ready, with markers (their ids those of `tracks`); `release_s`: as detected;
// `excluded`: marker ids the fit must not use. Throws InputError when no marker can be used or
// nothing moved.
PullFit FitPull(const Tree& tree, const Trajectories& tracks,
                const Eigen::Isometry3d& world_from_camera, double release_s,
                const std::vector<int>& excluded, const PullFitOptions& options = {});

}  // namespace simtree::pipeline::detail
