#pragma once
// The automatic budget on a MuJoCo step (step_cost.h): a tree whose model at the asked resolution
// would step slower than `min_steps_per_second` gets a coarser one, so a user exporting a large
// tree need not know the flags. The rungs, finest first: fewer segments per branch with twist
// hinges kept, down to 2; then at 2 and at 1 segment, without twist hinges. Segments go first:
// every chain is tuned to its branch's first modes at any segment count, so a coarser chain
// mostly loses higher modes and shape; a missing twist hinge loses a motion (a sub-tree swinging
// sideways can no longer twist its branch), and it is cheap to drop only late: at 1,000 branches
// twist hinges make a step 1.6-1.8x slower (docs/benchmarks.md). A resolution the user fixed is
// kept (over_budget says when it is estimated too slow).

#include <string>

#include "simtree/core/tree.h"
#include "simtree/robots/robot_model.h"
#include "simtree/robots/step_cost.h"

namespace simtree::robots {

struct StepBudgetOptions {
  // Estimated steps per second (bench_robots' machine) a model must reach; 0 = no budget. The
  // estimate ran 10% above the measured rate at 1,000 branches, so 1,200 for the 1,000;
  // tree01 (95 branches) keeps 4 segments and twist hinges (estimated 2,080, measured 2,240).
  double min_steps_per_second = 1200.0;
  bool fixed_segments = false;  // the user chose segments_per_branch: the budget keeps it
  bool fixed_twist = false;     // the user chose the twist hinges: the budget keeps them

  void Validate() const;  // throws OptionError naming the field
};

struct StepBudget {
  int asked_segments = 0;
  TwistHinges asked_twist = TwistHinges::kBranchesWithKids;
  int segments = 0;  // chosen
  TwistHinges twist = TwistHinges::kBranchesWithKids;
  StepCost asked_cost;  // of the asked resolution
  StepCost cost;        // of the chosen one
  bool reduced = false;
  double target_steps_per_second = 0.0;  // StepBudgetOptions::min_steps_per_second
  bool over_budget = false;              // even the chosen resolution is estimated below the target

  std::string Summary() const;  // one line: what was reduced and why
};

// The resolution to export `tree` at: `model`'s own when it fits (or there is no budget), else
// the finest rung that fits, else the coarsest the fixed choices allow (over_budget). Throws as
// BuildRobotModel does, naming `source`.
StepBudget ChooseStepBudget(const Tree& tree, const RobotModelOptions& model,
                            const StepBudgetOptions& options, const std::string& source = "tree");

}  // namespace simtree::robots
