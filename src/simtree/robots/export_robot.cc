#include "simtree/robots/export_robot.h"

#include "simtree/core/atomic_file.h"
#include "simtree/core/option_checks.h"

namespace simtree::robots {

void ExportOptions::Validate() const {
  CheckNested("model", model);
  CheckNested("budget", budget);
  CheckNested("calibration", calibration);
}

RobotModel MakeRobotModel(const Tree& tree, const ExportOptions& options, const std::string& source,
                          CalibrationReport* report, StepBudget* budget) {
  options.Validate();
  const StepBudget chosen = ChooseStepBudget(tree, options.model, options.budget, source);
  RobotModelOptions resolved = options.model;
  resolved.segments_per_branch = chosen.segments;
  resolved.twist = chosen.twist;
  RobotModel model = BuildRobotModel(tree, resolved, source);
  if (budget) *budget = chosen;
  const CalibrationReport calibration = CalibrateRobotModel(tree, options.calibration, &model);
  if (report) *report = calibration;
  return model;
}

ExportResult ExportRobot(const Tree& tree, const ExportOptions& options,
                         const std::filesystem::path& out, const std::string& source) {
  ExportResult result;
  const RobotModel model =
      MakeRobotModel(tree, options, source, &result.calibration, &result.budget);
  WriteFileAtomically(out, WriteRobotFormat(model, options.format));
  result.branches = tree.size();
  result.bodies = static_cast<int>(model.segments.size());
  result.hinges = model.HingeCount();
  result.sites = static_cast<int>(model.sites.size());
  result.segments_per_branch = model.segments_per_branch;
  result.total_mass_kg = model.total_mass_kg;
  result.time_step_s = model.time_step_s;
  return result;
}

}  // namespace simtree::robots
