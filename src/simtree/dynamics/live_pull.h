#pragma once
// A simulation advanced frame by frame with a pull test, as `simulate` runs it and the viewer
// plays it: each frame split into equal steps no longer than a maximum, and the pull's rope set
// before each step to the schedule at the step's start. So the viewer and `simulate` give the
// same motion for the same options.

#include <optional>

#include "simtree/core/tree.h"
#include "simtree/dynamics/simulate.h"
#include "simtree/dynamics/tree_dynamics.h"

namespace simtree::dynamics {

// A pull test played on a live simulation: the rope's full tension is found once from rest (a
// displacement pull becomes the tension that reaches it), then follows the schedule's ramp, hold
// and release.
class LivePull {
 public:
  LivePull() = default;  // no pull
  // `sim` should be at rest (time 0). Throws InputError for a rope the tree cannot take.
  LivePull(TreeDynamics& sim, const PullSchedule& schedule);

  bool active() const { return schedule_.has_value(); }
  // Sets the rope for the load at sim.time() (attaches, updates or releases it).
  void Apply(TreeDynamics& sim);
  // After sim.Reset(): the rope is gone; the schedule starts again.
  void Restart() { rope_id_ = -1; }
  // The rope now (-1 when none).
  int rope_id() const { return rope_id_; }
  double full_tension_n() const { return full_tension_; }

 private:
  std::optional<PullSchedule> schedule_;
  Rope rope_;
  double full_tension_ = 0.0;
  int rope_id_ = -1;
};

// Highest modal frequency of a tree's materials (Hz); 1 when it has none.
double HighestModeFrequency(const Tree& tree);

// The automatic longest step (s): 1 / (20 f_max), so loads and base accelerations held over a
// step stay smooth.
double AutomaticMaxStep(const Tree& tree);

// A frame of `frame_dt` seconds split into `steps` equal steps of `dt`, none longer than `max_dt`.
struct FrameSplit {
  int steps = 1;
  double dt = 0.0;
};
FrameSplit SplitFrame(double frame_dt, double max_dt);

// Advances `sim` by `frame_dt` in equal steps no longer than AutomaticMaxStep(), applying `pull`
// before each step. Returns the number of steps.
int AdvanceFrame(TreeDynamics& sim, LivePull& pull, double frame_dt);

}  // namespace simtree::dynamics
