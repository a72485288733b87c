#pragma once
// The simulation-ready tree for robot simulators (`simtree export`): MJCF (MuJoCo), URDF or SDF.
//
//  - Every branch is a chain of `segments_per_branch` rigid capsules (radius from the wood's
//    volume, mass from the wood density), joined at each segment's base by two bending hinges
//    (about the branch's w and u axes: its bend_u and bend_w modes) and, on branches that carry
//    children (or all, or none), a twist hinge about the segment; the trunk's base is hinged on
//    the world, nothing else moves it (robot_model.h).
//  - Hinge stiffness and damping make each branch's chain, with the sub-trees riding on it, ring
//    at its material's frequencies and damping ratios; spring references hold the scanned pose
//    under gravity (robot_calibration.h).
//  - Sites: `marker_<id>` at every tape marker, `grasp_b<id>` midway along every branch,
//    `tip_b<id>` at every tip.
//  - An automatic budget on a MuJoCo step's estimated cost (step_budget.h) gives large trees
//    fewer segments per branch, then no twist hinges, unless the user fixed them; `max_bodies`
//    caps the segment bodies.
//
// Usage:
//   const simtree::Tree tree = simtree::ReadTreeFile("simready.json");
//   simtree::robots::ExportOptions options;
//   options.format = simtree::robots::RobotFormat::kMjcf;
//   const auto result = simtree::robots::ExportRobot(tree, options, "tree.xml");

#include <filesystem>
#include <string>

#include "simtree/core/tree.h"
#include "simtree/robots/robot_calibration.h"
#include "simtree/robots/robot_formats.h"
#include "simtree/robots/robot_model.h"
#include "simtree/robots/step_budget.h"

namespace simtree::robots {

struct ExportOptions {
  RobotFormat format = RobotFormat::kMjcf;
  RobotModelOptions model;
  StepBudgetOptions budget;
  CalibrationOptions calibration;

  void Validate() const;  // throws OptionError naming the field ("model.segments_per_branch")
};

struct ExportResult {
  int branches = 0;
  int bodies = 0;  // segment bodies
  int hinges = 0;
  int sites = 0;
  int segments_per_branch = 0;  // after the budget
  double total_mass_kg = 0.0;
  double time_step_s = 0.0;  // the step written (MJCF) or recommended (URDF, SDF)
  StepBudget budget;         // the resolution asked and written, and why
  CalibrationReport calibration;
};

// The calibrated model at the budget's resolution, without writing it.
RobotModel MakeRobotModel(const Tree& tree, const ExportOptions& options,
                          const std::string& source = "tree", CalibrationReport* report = nullptr,
                          StepBudget* budget = nullptr);

// Writes `tree` in `options.format` to `out` (whole or not at all). Throws InputError naming
// `source` and the branch for a tree that cannot be exported (no material, a zero radius or
// length), OptionError for a bad option.
ExportResult ExportRobot(const Tree& tree, const ExportOptions& options,
                         const std::filesystem::path& out, const std::string& source = "tree");

}  // namespace simtree::robots
