#include "simtree/dynamics/simulate.h"

#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/progress.h"
#include "simtree/dynamics/live_pull.h"

namespace simtree::dynamics {
namespace {

void CheckSimulation(bool ok, const std::string& field, const std::string& message) {
  CheckOption(ok, "simulation options", field, message);
}

// Steps every frame after the first (the pull set before each step) and hands each frame to the
// recorders.
void RecordFrames(TreeDynamics& sim, LivePull& pull, const FrameSplit& split, int frames,
                  double frame_dt, std::span<FrameRecorder* const> recorders) {
  Progress progress("simulate", frames, "frames");
  for (int frame = 0; frame < frames; ++frame) {
    if (frame > 0) {
      for (int s = 0; s < split.steps; ++s) {
        pull.Apply(sim);
        sim.Step(split.dt);
      }
    }
    const double t = frame * frame_dt;
    for (FrameRecorder* r : recorders) r->Record(frame, t, sim);
    progress.Advance();
  }
  progress.Done();
}

}  // namespace

double PullSchedule::Factor(double time_s) const {
  if (time_s >= release_s) return 0.0;
  if (time_s >= hold_s) return 1.0;
  if (time_s <= 0.0) return hold_s <= 0.0 ? 1.0 : 0.0;
  const double x = time_s / hold_s;
  return x * x * (3.0 - 2.0 * x);
}

void PullSchedule::Validate() const {
  CheckOption(std::isfinite(hold_s) && hold_s >= 0.0, "pull schedule", "hold_s",
              fmt::format("expected the time the pull is full (hold) >= 0 s, got {}", hold_s));
  CheckOption(
      std::isfinite(release_s) && release_s >= hold_s, "pull schedule", "release_s",
      fmt::format("expected the release time >= the hold time ({} s), got {}", hold_s, release_s));
}

void SimulationOptions::Validate() const {
  CheckSimulation(std::isfinite(duration_s) && duration_s >= 0.0, "duration_s",
                  fmt::format("expected a duration >= 0 s, got {}", duration_s));
  CheckSimulation(std::isfinite(fps) && fps > 0.0 && fps <= 10000.0, "fps",
                  fmt::format("expected a frame rate in (0, 10000] per second, got {}", fps));
  CheckSimulation(std::isfinite(max_time_step_s) && max_time_step_s >= 0.0, "max_time_step_s",
                  fmt::format("expected a step >= 0 s (0 = automatic), got {}", max_time_step_s));
  CheckSimulation(duration_s * fps <= 1e7, "duration_s",
                  fmt::format("expected at most 10 million frames, got {:.0f}", duration_s * fps));
  if (pull) pull->Validate();
  dynamics.Validate();
}

int FrameCount(double duration_s, double fps) {
  return static_cast<int>(std::floor(duration_s * fps + 1e-9)) + 1;
}

void ValidateSimulation(const Tree& tree, const SimulationOptions& options) {
  options.Validate();
  if (options.pull) ValidateRope(tree, options.pull->rope, "pull");
  ValidateForSimulation(tree, "tree");
}

SimulationResult RunSimulation(const Tree& tree, const SimulationOptions& options,
                               std::span<FrameRecorder* const> recorders) {
  ValidateSimulation(tree, options);

  SimulationResult result;
  const auto start = std::chrono::steady_clock::now();
  TreeDynamics sim(tree, options.dynamics);
  const double frame_dt = 1.0 / options.fps;
  const FrameSplit split =
      SplitFrame(frame_dt, options.max_time_step_s > 0.0 ? options.max_time_step_s
                                                         : AutomaticMaxStep(sim.tree()));
  result.time_step_s = split.dt;
  result.frames = FrameCount(options.duration_s, options.fps);

  // The rope pulls with its full tension scaled by the schedule; a displacement pull is turned
  // into the tension that reaches it from rest.
  LivePull pull;
  if (options.pull) {
    pull = LivePull(sim, *options.pull);
    result.pull_tension_n = pull.full_tension_n();
    const Rope& rope = options.pull->rope;
    const double s = rope.arc_length < 0.0 ? tree.branches[rope.branch].Length() : rope.arc_length;
    result.pull_point = tree.branches[rope.branch].PointAt(s);
  }

  for (FrameRecorder* r : recorders) r->Begin(sim, result.frames, options.fps);
  RecordFrames(sim, pull, split, result.frames, frame_dt, recorders);
  for (FrameRecorder* r : recorders) r->End();
  result.steps = sim.steps();
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  spdlog::debug("simulated {} frames, {} steps of {:.4g} s in {:.3g} s", result.frames,
                result.steps, split.dt, result.wall_seconds);
  return result;
}

}  // namespace simtree::dynamics
