#include "simtree/dynamics/live_pull.h"

#include <algorithm>
#include <cmath>

namespace simtree::dynamics {

LivePull::LivePull(TreeDynamics& sim, const PullSchedule& schedule) : schedule_(schedule) {
  rope_ = schedule.rope;
  const int probe = sim.AttachRope(rope_);
  full_tension_ = sim.RopeTension(probe);
  sim.ReleaseRope(probe);
  rope_.mode = Rope::Mode::kForce;
}

void LivePull::Apply(TreeDynamics& sim) {
  if (!schedule_) return;
  if (rope_id_ >= 0 && !sim.HasRope(rope_id_)) rope_id_ = -1;  // released by someone else
  const double factor = schedule_->Factor(sim.time());
  if (factor <= 0.0) {
    if (rope_id_ >= 0) sim.ReleaseRope(rope_id_);
    rope_id_ = -1;
    return;
  }
  rope_.force_n = factor * full_tension_;
  if (rope_id_ < 0) {
    rope_id_ = sim.AttachRope(rope_);
  } else {
    sim.UpdateRope(rope_id_, rope_);
  }
}

double HighestModeFrequency(const Tree& tree) {
  double f = 0.0;
  for (const Branch& b : tree.branches) {
    if (!b.material) continue;
    for (const Mode& m : b.material->modes) f = std::max(f, m.frequency_hz);
  }
  return f > 0.0 ? f : 1.0;
}

double AutomaticMaxStep(const Tree& tree) { return 1.0 / (20.0 * HighestModeFrequency(tree)); }

FrameSplit SplitFrame(double frame_dt, double max_dt) {
  FrameSplit split;
  split.steps = std::max(1, static_cast<int>(std::ceil(frame_dt / max_dt - 1e-9)));
  split.dt = frame_dt / split.steps;
  return split;
}

int AdvanceFrame(TreeDynamics& sim, LivePull& pull, double frame_dt) {
  if (!(frame_dt > 0.0)) return 0;
  const FrameSplit split = SplitFrame(frame_dt, AutomaticMaxStep(sim.tree()));
  for (int i = 0; i < split.steps; ++i) {
    pull.Apply(sim);
    sim.Step(split.dt);
  }
  return split.steps;
}

}  // namespace simtree::dynamics
