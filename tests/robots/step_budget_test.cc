// The automatic step budget: trees exported today keep their resolution, a 1,000-branch tree is
// reduced to under the budget, and what the user fixed is kept.

#include "simtree/robots/step_budget.h"

#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "robots/authors_tree.h"
#include "simtree/core/frames.h"
#include "simtree/core/option_checks.h"
#include "simtree/robots/export_robot.h"
#include "simtree/synth/detail/tree_generator.h"
#include "simtree/synth/species.h"
#include "test_util.h"

namespace simtree::robots {
namespace {

void GiveMaterials(Tree* tree) {
  for (Branch& b : tree->branches) {
    b.material = Material::FromFrequencyDampingStiffness(
        b.is_trunk() ? 3.0 : 1.2, 0.04, b.is_trunk() ? 5000.0 : 50.0, MaterialSource::kAssumed);
  }
}

// Every branch forks into three at its middle and tip until `count` branches (bench_robots'
// tree: 7 levels at 1,000).
Tree ForkingTree(int count) {
  Tree tree;
  Branch trunk;
  trunk.nodes = {{Eigen::Vector3d(0, 0, 0), 0.08},
                 {Eigen::Vector3d(0, 0, 0.8), 0.07},
                 {Eigen::Vector3d(0, 0, 1.6), 0.06}};
  tree.branches.push_back(trunk);
  for (int id = 0; static_cast<int>(tree.branches.size()) < count; ++id) {
    const Branch parent = tree.branches[id];
    const Eigen::Vector3d along = parent.tip().position - parent.base().position;
    const Eigen::Vector3d axis = along.normalized();
    const Eigen::Vector3d side_u = axis.unitOrthogonal(), side_w = axis.cross(side_u);
    for (int k = 0; k < 3 && static_cast<int>(tree.branches.size()) < count; ++k) {
      const int node = k == 0 ? 1 : 2;
      const double angle = 2.1 * k + 0.5 * id;
      const Eigen::Vector3d direction =
          (axis + 0.8 * (std::cos(angle) * side_u + std::sin(angle) * side_w)).normalized();
      const Eigen::Vector3d base = parent.nodes[node].position;
      const double length = 0.7 * along.norm(), radius = 0.6 * parent.nodes[node].radius;
      Branch child;
      child.id = static_cast<int>(tree.branches.size());
      child.parent = id;
      child.parent_node = node;
      child.nodes = {{base, radius},
                     {base + 0.5 * length * direction, 0.8 * radius},
                     {base + length * direction, 0.6 * radius}};
      tree.branches.push_back(child);
    }
  }
  AssignLevels(tree);
  ComputeFrames(tree);
  GiveMaterials(&tree);
  return tree;
}

TEST(StepBudget, TreesExportedTodayKeepTheirResolution) {
  const ExportOptions defaults;
  const StepBudget tree01 =
      ChooseStepBudget(test::AuthorsTree01(), defaults.model, defaults.budget);
  EXPECT_FALSE(tree01.reduced) << tree01.Summary();
  EXPECT_EQ(tree01.segments, 4);
  EXPECT_EQ(tree01.twist, TwistHinges::kBranchesWithKids);
  for (const char* preset : {"acer_palmatum", "magnolia", "acer_rubrum"}) {
    for (uint64_t seed : {1, 2}) {
      // Reconstructed synth trees are 10-60 branches (the scans' thinnest twigs are pruned).
      synth::GeneratorOptions grow;
      grow.max_branches = 60;
      Tree tree = synth::GenerateTree(synth::SpeciesPreset(preset), seed, grow);
      GiveMaterials(&tree);
      const StepBudget budget = ChooseStepBudget(tree, defaults.model, defaults.budget);
      EXPECT_FALSE(budget.reduced)
          << preset << " " << seed << " (" << tree.size() << " branches): " << budget.Summary();
    }
  }
}

TEST(StepBudget, ThousandBranchTreeIsReducedUnderTheBudget) {
  const Tree tree = ForkingTree(1000);
  const ExportOptions defaults;
  const StepBudget budget = ChooseStepBudget(tree, defaults.model, defaults.budget);
  EXPECT_TRUE(budget.reduced);
  EXPECT_FALSE(budget.over_budget) << budget.Summary();
  EXPECT_LT(budget.segments, 4);
  EXPECT_GE(budget.cost.steps_per_second, defaults.budget.min_steps_per_second);
  EXPECT_LT(budget.asked_cost.steps_per_second, defaults.budget.min_steps_per_second);
  // The model built is the one the budget chose and costed.
  const RobotModel model = MakeRobotModel(tree, defaults);
  EXPECT_EQ(model.segments.size(), static_cast<size_t>(budget.segments * tree.size()));
  EXPECT_EQ(EstimateStepCost(model).depth_sq_sum, budget.cost.depth_sq_sum);
}

TEST(StepBudget, ExplicitResolutionIsKeptAndFlaggedOverBudget) {
  const Tree tree = ForkingTree(1000);
  ExportOptions options;
  options.model.segments_per_branch = 3;
  options.budget.fixed_segments = true;
  options.budget.fixed_twist = true;
  const StepBudget fixed = ChooseStepBudget(tree, options.model, options.budget);
  EXPECT_FALSE(fixed.reduced);
  EXPECT_TRUE(fixed.over_budget);
  EXPECT_EQ(fixed.segments, 3);
  EXPECT_EQ(fixed.twist, TwistHinges::kBranchesWithKids);
  // Segments fixed, twist free: only the twist hinges go.
  options.budget.fixed_twist = false;
  const StepBudget twist_free = ChooseStepBudget(tree, options.model, options.budget);
  EXPECT_EQ(twist_free.segments, 3);
  EXPECT_EQ(twist_free.twist, TwistHinges::kNone);
  // No budget: as asked.
  options.budget = {};
  options.budget.min_steps_per_second = 0;
  EXPECT_FALSE(ChooseStepBudget(tree, options.model, options.budget).reduced);
}

TEST(StepBudget, NegativeTargetIsRefused) {
  ExportOptions options;
  options.budget.min_steps_per_second = -1;
  EXPECT_THROW(options.Validate(), OptionError);
}

}  // namespace
}  // namespace simtree::robots
