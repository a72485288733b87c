#pragma once
// The options of a simulation run, shared by every verb that runs one (simulate, view, render):
// the pull test (--pull, --force, --displacement, --anchor, --direction, --hold, --release), the
// wind, the model switches and the run's length and rate.

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "simtree/core/tree.h"
#include "simtree/dynamics/simulate.h"

namespace simtree::cli {

struct SimulationArgs {
  dynamics::SimulationOptions sim;
  std::string pull, integrator = "exact";
  std::optional<double> force, displacement;
  std::vector<double> anchor, direction;
  double hold = 1.0, release = 3.0;
  double wind = 0.0, wind_heading_deg = 0.0;
  bool no_base_excitation = false, no_transfer = false;
};

// --pull BRANCH[@S], --force, --displacement, --anchor, --direction, --hold, --release.
void AddPullOptions(CLI::App* verb, SimulationArgs& args);
// --wind, --wind-heading-deg, --turbulence, --gust-length, --wind-seed.
void AddWindOptions(CLI::App* verb, SimulationArgs& args);
// --gravity, --no-base-excitation, --no-load-transfer, --demo-mode-spread, --integrator.
void AddModelOptions(CLI::App* verb, SimulationArgs& args);
// --duration, --fps, --time-step.
void AddRunOptions(CLI::App* verb, SimulationArgs& args);

// Turns the parsed options into args.sim (pull schedule, wind, model) for `tree`. Throws
// InputError for contradictory or out-of-range values, naming the option.
void FinishSimulationArgs(const Tree& tree, SimulationArgs& args);

}  // namespace simtree::cli
