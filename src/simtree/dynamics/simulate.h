#pragma once
// A whole simulation run, as `simtree simulate` does it: a pull test (ramp a rope up, hold it,
// release it), optional wind, stepped at a fixed step and sampled at a frame rate into any number
// of recorders (node positions, markers, a glTF animation; see recorders.h).
//
// Usage:
//   simtree::dynamics::SimulationOptions options;
//   options.duration_s = 10.0;
//   simtree::dynamics::AnimationRecorder animation("animation.glb", {});
//   simtree::dynamics::FrameRecorder* recorders[] = {&animation};
//   simtree::dynamics::RunSimulation(tree, options, recorders);

#include <optional>
#include <span>
#include <vector>

#include "simtree/dynamics/rope.h"
#include "simtree/dynamics/tree_dynamics.h"

namespace simtree::dynamics {

// The pull test of paper Section III-C: the rope's force (or displacement) ramps up smoothly from
// nothing at t = 0 to full at `hold_s`, is held, and is let go at once at `release_s`.
struct PullSchedule {
  Rope rope;               // at full force or displacement
  double hold_s = 1.0;     // full from here on (0 = at once)
  double release_s = 3.0;  // let go here (>= hold_s; past the end = never)

  // The fraction of the full rope at time t: a smoothstep ramp, 1 while held, 0 once released.
  double Factor(double time_s) const;
};

struct SimulationOptions {
  double duration_s = 10.0;
  double fps = 30.0;
  // Longest simulation step (s); 0 = automatic: each frame interval split into equal steps no
  // longer than 1 / (20 f_max), f_max the tree's highest modal frequency, so loads and base
  // accelerations held over a step stay smooth.
  double max_time_step_s = 0.0;
  std::optional<PullSchedule> pull;
  DynamicsOptions dynamics;
};

// Receives the simulation at every frame (frame 0 is t = 0, before any step).
class FrameRecorder {
 public:
  virtual ~FrameRecorder() = default;
  virtual void Begin(const TreeDynamics& sim, int frame_count, double fps) {}
  virtual void Record(int frame, double time_s, const TreeDynamics& sim) = 0;
  virtual void End() {}
};

struct SimulationResult {
  int frames = 0;
  int64_t steps = 0;
  double time_step_s = 0.0;
  double pull_tension_n = 0.0;  // the full rope tension (N) the pull reached
  Eigen::Vector3d pull_point = Eigen::Vector3d::Zero();  // rest position of the pulled point
  double wall_seconds = 0.0;
};

// Throws InputError (before any work) for negative or non-finite durations, a frame rate <= 0,
// a release before the hold, an unknown pull branch, and for a tree that cannot be simulated.
SimulationResult RunSimulation(const Tree& tree, const SimulationOptions& options,
                               std::span<FrameRecorder* const> recorders);

// The frames a run gives: t = 0 and every 1 / fps up to the duration.
int FrameCount(double duration_s, double fps);

}  // namespace simtree::dynamics
