#pragma once
// A pull test played on a live simulation the way RunSimulation plays it (simulation.h): the
// rope's full tension is found once from rest (a displacement pull becomes the tension that
// reaches it), then follows the schedule's ramp, hold and release, the load of each step being the
// schedule at its start. So the viewer and `simulate` give the same motion for the same options.

#include <optional>

#include "simtree/dynamics/simulate.h"
#include "simtree/dynamics/tree_dynamics.h"

namespace simtree::viewer {

class LivePull {
 public:
  LivePull() = default;
  // `sim` should be at rest (time 0). Throws InputError for a rope the tree cannot take.
  LivePull(dynamics::TreeDynamics& sim, const dynamics::PullSchedule& schedule);

  bool active() const { return schedule_.has_value(); }
  // Sets the rope for the load at sim.time() (attaches, updates or releases it).
  void Apply(dynamics::TreeDynamics& sim);
  // After sim.Reset(): the rope is gone; the schedule starts again.
  void Restart() { rope_id_ = -1; }
  // The rope now (-1 when none).
  int rope_id() const { return rope_id_; }
  double full_tension_n() const { return full_tension_; }

 private:
  std::optional<dynamics::PullSchedule> schedule_;
  dynamics::Rope rope_;
  double full_tension_ = 0.0;
  int rope_id_ = -1;
};

// Highest modal frequency of a tree's materials (Hz); 1 when it has none.
double HighestModeFrequency(const Tree& tree);

// Advances `sim` by `frame_dt` in equal steps no longer than 1 / (20 f_max), applying `pull`
// before each step. Returns the number of steps.
int AdvanceFrame(dynamics::TreeDynamics& sim, LivePull& pull, double frame_dt);

}  // namespace simtree::viewer
