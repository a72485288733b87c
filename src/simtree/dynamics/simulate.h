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
  double hold_s = 1.0;     // full from here on (s, >= 0; 0 = at once)
  double release_s = 3.0;  // let go here (s, >= hold_s; past the end = never)

  // The fraction of the full rope at time t: a smoothstep ramp, 1 while held, 0 once released.
  double Factor(double time_s) const;
  // Throws InputError ("pull schedule", the field) for times that are negative, not finite or
  // out of order. The rope is checked against its tree by ValidateRope().
  void Validate() const;
};

struct SimulationOptions {
  double duration_s = 10.0;  // simulated time (s, >= 0)
  double fps = 30.0;         // frames recorded per simulated second (in (0, 10000])
  // Longest simulation step (s, >= 0); 0 = automatic: each frame interval split into equal steps
  // no longer than 1 / (20 f_max), f_max the tree's highest modal frequency, so loads and base
  // accelerations held over a step stay smooth.
  double max_time_step_s = 0.0;
  std::optional<PullSchedule> pull;  // none: the tree only moves under wind (or gravity)
  DynamicsOptions dynamics;          // the model's switches, its integrator and the wind

  // Throws InputError ("simulation options", the field) for a value out of range: a negative or
  // non-finite duration or step, a frame rate outside (0, 10000], more than 10 million frames, a
  // bad pull schedule or bad dynamics options.
  void Validate() const;
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
  int frames = 0;               // recorded, frame 0 at t = 0 included
  int64_t steps = 0;            // simulation steps taken
  double time_step_s = 0.0;     // the length of every step (s)
  double pull_tension_n = 0.0;  // the full rope tension (N) the pull reached
  Eigen::Vector3d pull_point = Eigen::Vector3d::Zero();  // rest position of the pulled point (m)
  double wall_seconds = 0.0;                             // wall-clock time of the run
};

// The checks RunSimulation makes before any work: options.Validate(), the pull's rope against the
// tree (ValidateRope) and ValidateForSimulation(tree, "tree").
void ValidateSimulation(const Tree& tree, const SimulationOptions& options);

// Runs the simulation and hands every frame to the recorders. Throws InputError (before any work)
// as ValidateSimulation does.
SimulationResult RunSimulation(const Tree& tree, const SimulationOptions& options,
                               std::span<FrameRecorder* const> recorders);

// The frames a run gives: t = 0 and every 1 / fps up to the duration.
int FrameCount(double duration_s, double fps);

}  // namespace simtree::dynamics
