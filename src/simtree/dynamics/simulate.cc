#include "simtree/dynamics/simulate.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/core/progress.h"

namespace simtree::dynamics {
namespace {

void Check(bool ok, const std::string& field, const std::string& message) {
  if (!ok) throw InputError("simulation options", field, message);
}

double HighestFrequency(const Tree& tree) {
  double f = 0.0;
  for (const Branch& b : tree.branches) {
    for (const Mode& m : b.material->modes) f = std::max(f, m.frequency_hz);
  }
  return f;
}

}  // namespace

double PullSchedule::Factor(double time_s) const {
  if (time_s >= release_s) return 0.0;
  if (time_s >= hold_s) return 1.0;
  if (time_s <= 0.0) return hold_s <= 0.0 ? 1.0 : 0.0;
  const double x = time_s / hold_s;
  return x * x * (3.0 - 2.0 * x);
}

int FrameCount(double duration_s, double fps) {
  return static_cast<int>(std::floor(duration_s * fps + 1e-9)) + 1;
}

SimulationResult RunSimulation(const Tree& tree, const SimulationOptions& options,
                               std::span<FrameRecorder* const> recorders) {
  Check(std::isfinite(options.duration_s) && options.duration_s >= 0.0, "duration_s",
        fmt::format("expected a duration >= 0 s, got {}", options.duration_s));
  Check(std::isfinite(options.fps) && options.fps > 0.0 && options.fps <= 10000.0, "fps",
        fmt::format("expected a frame rate in (0, 10000] per second, got {}", options.fps));
  Check(std::isfinite(options.max_time_step_s) && options.max_time_step_s >= 0.0, "max_time_step_s",
        fmt::format("expected a step >= 0 s (0 = automatic), got {}", options.max_time_step_s));
  Check(options.duration_s * options.fps <= 1e7, "duration_s",
        fmt::format("expected at most 10 million frames, got {:.0f}",
                    options.duration_s * options.fps));
  if (options.pull) {
    const PullSchedule& p = *options.pull;
    Check(std::isfinite(p.hold_s) && p.hold_s >= 0.0, "hold_s",
          fmt::format("expected the time the pull is full (hold) >= 0 s, got {}", p.hold_s));
    Check(std::isfinite(p.release_s) && p.release_s >= p.hold_s, "release_s",
          fmt::format("expected the release time >= the hold time ({} s), got {}", p.hold_s,
                      p.release_s));
    ValidateRope(tree, p.rope, "pull");
  }
  ValidateForSimulation(tree, "tree");

  SimulationResult result;
  const auto start = std::chrono::steady_clock::now();
  TreeDynamics sim(tree, options.dynamics);
  const double frame_dt = 1.0 / options.fps;
  const double max_dt = options.max_time_step_s > 0.0 ? options.max_time_step_s
                                                      : 1.0 / (20.0 * HighestFrequency(sim.tree()));
  const int substeps = std::max(1, static_cast<int>(std::ceil(frame_dt / max_dt - 1e-9)));
  const double dt = frame_dt / substeps;
  result.time_step_s = dt;
  result.frames = FrameCount(options.duration_s, options.fps);

  // The rope pulls with its full tension scaled by the schedule; a displacement pull is turned
  // into the tension that reaches it from rest.
  int rope_id = -1;
  Rope rope;
  double full_tension = 0.0;
  if (options.pull) {
    rope = options.pull->rope;
    rope_id = sim.AttachRope(rope);
    full_tension = sim.RopeTension(rope_id);
    sim.ReleaseRope(rope_id);
    rope_id = -1;
    rope.mode = Rope::Mode::kForce;
    result.pull_tension_n = full_tension;
    const double s = rope.arc_length < 0.0 ? tree.branches[rope.branch].Length() : rope.arc_length;
    result.pull_point = tree.branches[rope.branch].PointAt(s);
  }
  auto apply_pull = [&](double t) {
    if (!options.pull) return;
    const double factor = options.pull->Factor(t);
    if (factor <= 0.0) {
      if (rope_id >= 0) sim.ReleaseRope(rope_id);
      rope_id = -1;
      return;
    }
    rope.force_n = factor * full_tension;
    if (rope_id < 0) {
      rope_id = sim.AttachRope(rope);
    } else {
      sim.UpdateRope(rope_id, rope);
    }
  };

  for (FrameRecorder* r : recorders) r->Begin(sim, result.frames, options.fps);
  Progress progress("simulate", result.frames, "frames");
  for (int frame = 0; frame < result.frames; ++frame) {
    if (frame > 0) {
      for (int s = 0; s < substeps; ++s) {
        // The load of a step is the schedule at its start.
        apply_pull(sim.time());
        sim.Step(dt);
      }
    }
    const double t = frame * frame_dt;
    for (FrameRecorder* r : recorders) r->Record(frame, t, sim);
    progress.Advance();
  }
  progress.Done();
  for (FrameRecorder* r : recorders) r->End();
  result.steps = sim.steps();
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  spdlog::debug("simulated {} frames, {} steps of {:.4g} s in {:.3g} s", result.frames,
                result.steps, dt, result.wall_seconds);
  return result;
}

}  // namespace simtree::dynamics
