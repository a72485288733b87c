#include "sim_options.h"

#include <cmath>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/units.h"
#include "simtree/dynamics/rope.h"

namespace simtree::cli {
namespace {

Eigen::Vector3d Vector(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

}  // namespace

void AddPullOptions(CLI::App* verb, SimulationArgs& args) {
  auto* pull = verb->add_option_group("pull test");
  pull->add_option("--pull", args.pull,
                   "Branch to pull: BRANCH (its tip) or BRANCH@S (S metres from its base)");
  pull->add_option("--force", args.force, "Rope tension at full pull (N)");
  pull->add_option("--displacement", args.displacement,
                   "Instead of a force: pull until the point has moved this far towards the "
                   "anchor, statically (m)");
  pull->add_option("--anchor", args.anchor,
                   "Where the rope is tied: X,Y,Z (world, m). Default: 2 m from the point, "
                   "straight down (sideways for an upright branch)")
      ->expected(3)
      ->delimiter(',');
  pull->add_option("--direction", args.direction,
                   "Instead of an anchor: the pull direction X,Y,Z (anchor 2 m that way)")
      ->expected(3)
      ->delimiter(',');
  pull->add_option("--hold", args.hold,
                   "Time (s) the pull is full and held from; it ramps up smoothly from t = 0 "
                   "(0 = all at once)")
      ->capture_default_str();
  pull->add_option("--release", args.release, "Time (s) the rope is let go")->capture_default_str();
}

void AddWindOptions(CLI::App* verb, SimulationArgs& args) {
  auto* wind = verb->add_option_group("wind");
  wind->add_option("--wind", args.wind,
                   "Mean wind speed at the top of the crown (m/s); 0 = no wind")
      ->capture_default_str();
  wind->add_option("--wind-heading-deg", args.wind_heading_deg,
                   "Direction the wind blows towards, degrees counter-clockwise from +X")
      ->capture_default_str();
  wind->add_option("--turbulence", args.sim.dynamics.wind.turbulence_intensity,
                   "Gust strength: standard deviation over mean speed")
      ->capture_default_str();
  wind->add_option("--gust-length", args.sim.dynamics.wind.length_scale_m,
                   "Size of the gusts (m); 0 = the tree's height")
      ->capture_default_str();
  wind->add_option("--wind-seed", args.sim.dynamics.wind.seed, "Same seed, same gusts")
      ->capture_default_str();
}

void AddModelOptions(CLI::App* verb, SimulationArgs& args) {
  auto* model = verb->add_option_group("model");
  model
      ->add_option("--integrator", args.integrator,
                   "exact (unconditionally stable), semi-implicit-euler (the authors' demo) or "
                   "explicit-euler (the paper's text; diverges for stiff branches)")
      ->capture_default_str();
  model->add_flag("--gravity", args.sim.dynamics.gravity,
                  "Let the tree sag under its own weight first (a scanned tree already has)");
  model->add_flag("--no-base-excitation", args.no_base_excitation,
                  "Children only ride their parents; their base's acceleration does not swing "
                  "them");
  model->add_flag("--no-load-transfer", args.no_transfer,
                  "A load bends only its own branch, not the ancestors");
  model->add_flag("--demo-mode-spread", args.sim.dynamics.demo_mode_spread,
                  "Spread each branch's modes as the authors' demo does (0.95 f, 1.05 f, f)");
}

void AddRunOptions(CLI::App* verb, SimulationArgs& args) {
  verb->add_option("--duration", args.sim.duration_s, "Simulated time (s)")->capture_default_str();
  verb->add_option("--fps", args.sim.fps, "Frames per second")->capture_default_str();
  verb->add_option("--time-step", args.sim.max_time_step_s,
                   "Longest simulation step (s); 0 = automatic, 1/20 of the fastest mode's period")
      ->capture_default_str();
}

void FinishSimulationArgs(const Tree& tree, SimulationArgs& args) {
  dynamics::SimulationOptions& sim = args.sim;
  sim.dynamics.integrator = dynamics::ParseIntegrator(args.integrator, "--integrator");
  sim.dynamics.base_excitation = !args.no_base_excitation;
  sim.dynamics.transfer_loads = !args.no_transfer;
  if (args.wind < 0.0 || !std::isfinite(args.wind)) {
    throw InputError("", "--wind", fmt::format("expected a speed >= 0 m/s, got {}", args.wind));
  }
  sim.dynamics.wind.enabled = args.wind > 0.0;
  sim.dynamics.wind.mean_speed_mps = args.wind;
  const double heading = DegToRad(args.wind_heading_deg);
  sim.dynamics.wind.direction = {std::cos(heading), std::sin(heading), 0.0};

  if (args.pull.empty()) {
    if (args.force || args.displacement || !args.anchor.empty() || !args.direction.empty()) {
      throw InputError("", "--pull",
                       "--force, --displacement, --anchor and --direction need --pull");
    }
    sim.pull.reset();
    return;
  }
  if (args.force.has_value() == args.displacement.has_value()) {
    throw InputError("", "--pull", "expected exactly one of --force N and --displacement M");
  }
  if (!args.anchor.empty() && !args.direction.empty()) {
    throw InputError("", "--anchor", "expected --anchor or --direction, not both");
  }
  const dynamics::PullTarget target = dynamics::ParsePullTarget(args.pull);
  dynamics::PullSchedule schedule;
  schedule.rope.branch = target.branch;
  schedule.rope.arc_length = target.arc_length;
  if (args.force) {
    schedule.rope.force_n = *args.force;
  } else {
    schedule.rope.mode = dynamics::Rope::Mode::kDisplacement;
    schedule.rope.displacement_m = *args.displacement;
  }
  const double s = dynamics::ValidateRope(tree, schedule.rope, "--pull");
  const Eigen::Vector3d point = tree.branches[target.branch].PointAt(s);
  if (!args.anchor.empty()) {
    schedule.rope.anchor = Vector(args.anchor);
  } else {
    const Eigen::Vector3d d = args.direction.empty()
                                  ? dynamics::DefaultPullDirection(tree, target.branch, s)
                                  : Vector(args.direction);
    if (!d.allFinite() || d.norm() < 1e-12) {
      throw InputError("", "--direction", "expected a non-zero finite direction");
    }
    schedule.rope.anchor = point + 2.0 * d.normalized();
  }
  dynamics::ValidateRope(tree, schedule.rope, "--pull");
  schedule.hold_s = args.hold;
  schedule.release_s = args.release;
  sim.pull = schedule;
}

}  // namespace simtree::cli
