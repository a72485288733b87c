#include "simtree/viewer/detail/live_pull.h"

#include <algorithm>
#include <cmath>

namespace simtree::viewer {

LivePull::LivePull(dynamics::TreeDynamics& sim, const dynamics::PullSchedule& schedule)
    : schedule_(schedule) {
  rope_ = schedule.rope;
  const int probe = sim.AttachRope(rope_);
  full_tension_ = sim.RopeTension(probe);
  sim.ReleaseRope(probe);
  rope_.mode = dynamics::Rope::Mode::kForce;
}

void LivePull::Apply(dynamics::TreeDynamics& sim) {
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

int AdvanceFrame(dynamics::TreeDynamics& sim, LivePull& pull, double frame_dt) {
  if (!(frame_dt > 0.0)) return 0;
  const double max_dt = 1.0 / (20.0 * HighestModeFrequency(sim.tree()));
  const int steps = std::max(1, static_cast<int>(std::ceil(frame_dt / max_dt - 1e-9)));
  const double dt = frame_dt / steps;
  for (int i = 0; i < steps; ++i) {
    pull.Apply(sim);
    sim.Step(dt);
  }
  return steps;
}

}  // namespace simtree::viewer
