#include "simtree/robots/step_budget.h"

#include <utility>
#include <vector>

#include <fmt/format.h>

#include "simtree/core/option_checks.h"

namespace simtree::robots {
namespace {

using Rung = std::pair<int, TwistHinges>;

// Finest first (step_budget.h says why segments go before twist hinges).
std::vector<Rung> Rungs(const RobotModelOptions& model, const StepBudgetOptions& options) {
  std::vector<Rung> rungs;
  const int lowest = options.fixed_segments ? model.segments_per_branch : 1;
  for (int segments = model.segments_per_branch; segments >= lowest; --segments) {
    rungs.emplace_back(segments, model.twist);
    const bool drop_twist = segments <= 2 || segments == lowest;
    if (drop_twist && !options.fixed_twist && model.twist != TwistHinges::kNone) {
      rungs.emplace_back(segments, TwistHinges::kNone);
    }
  }
  return rungs;
}

StepCost CostAt(const Tree& tree, RobotModelOptions model, const Rung& rung) {
  model.segments_per_branch = rung.first;
  model.twist = rung.second;
  return EstimateStepCost(BuildRobotModel(tree, model));
}

std::string Resolution(int segments, TwistHinges twist) {
  return fmt::format("{} segment{}, twist {}", segments, segments == 1 ? "" : "s", ToString(twist));
}

}  // namespace

void StepBudgetOptions::Validate() const {
  CheckNonNegative("min_steps_per_second", min_steps_per_second);
}

std::string StepBudget::Summary() const {
  if (over_budget) {
    return fmt::format("{} per branch: estimated {:.0f} steps/s, below the budget's {:.0f} ({})",
                       Resolution(segments, twist), cost.steps_per_second, target_steps_per_second,
                       reduced ? "the coarsest the fixed flags allow" : "kept as asked");
  }
  if (!reduced) {
    return fmt::format("{} per branch: estimated {:.0f} steps/s", Resolution(segments, twist),
                       cost.steps_per_second);
  }
  return fmt::format(
      "reduced to {} per branch, estimated {:.0f} steps/s: the asked {} was estimated at {:.0f}, "
      "below the budget's {:.0f}",
      Resolution(segments, twist), cost.steps_per_second, Resolution(asked_segments, asked_twist),
      asked_cost.steps_per_second, target_steps_per_second);
}

StepBudget ChooseStepBudget(const Tree& tree, const RobotModelOptions& model,
                            const StepBudgetOptions& options, const std::string& source) {
  options.Validate();
  StepBudget budget;
  budget.asked_segments = budget.segments = model.segments_per_branch;
  budget.asked_twist = budget.twist = model.twist;
  budget.asked_cost = budget.cost = EstimateStepCost(BuildRobotModel(tree, model, source));
  const double target = budget.target_steps_per_second = options.min_steps_per_second;
  if (target <= 0 || budget.asked_cost.steps_per_second >= target) return budget;
  const std::vector<Rung> rungs = Rungs(model, options);
  for (size_t i = 1; i < rungs.size(); ++i) {
    budget.segments = rungs[i].first;
    budget.twist = rungs[i].second;
    budget.cost = CostAt(tree, model, rungs[i]);
    budget.reduced = true;
    if (budget.cost.steps_per_second >= target) return budget;
  }
  budget.over_budget = true;
  return budget;
}

}  // namespace simtree::robots
