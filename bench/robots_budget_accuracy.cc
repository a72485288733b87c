// What the step budget costs in ringing: first-level branches pulled at their tip along u by 3% of
// their length, released, and their tip's ringing read in MuJoCo at several resolutions (segments
// per branch / twist hinges), against their material's first frequency and damping ratio.
//   build/bin/bench_robots_budget_accuracy            # tree01 and the 1,000-branch ternary tree
// Prints one row per tree, resolution and branch (the resolution the budget picks is marked).

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "robots_ternary_tree.h"
#include "simtree/core/tree_file.h"
#include "simtree/core/units.h"
#include "simtree/robots/export_robot.h"
#include "simtree/robots/mujoco_pull.h"

namespace {

using simtree::robots::TwistHinges;

struct Resolution {
  int segments;
  TwistHinges twist;
};

double SubtreeMassOf(const simtree::Tree& tree, const simtree::robots::RobotModel& model,
                     int branch) {
  const auto children = tree.Children();
  double mass = 0.0;
  std::vector<int> stack = {branch};
  while (!stack.empty()) {
    const int b = stack.back();
    stack.pop_back();
    for (int id : model.branch_segments[b]) mass += model.segments[id].mass_kg;
    for (int c : children[b]) stack.push_back(c);
  }
  return mass;
}

simtree::robots::Ringing PullTip(const simtree::Tree& tree,
                                 const simtree::robots::RobotModel& model,
                                 const std::filesystem::path& xml, int branch) {
  const simtree::Branch& b = tree.branches[branch];
  const double omega = simtree::kTwoPi * b.material->modes[0].frequency_hz;
  simtree::robots::MujocoPullOptions pull;
  pull.pull_site = fmt::format("tip_b{}", branch);
  pull.force =
      0.25 * SubtreeMassOf(tree, model, branch) * omega * omega * 0.03 * b.Length() * b.frame.u;
  pull.hold_s = 0.5;
  pull.release_s = 1.5;
  pull.duration_s = 7.5;
  pull.record_sites = {pull.pull_site};
  return simtree::robots::MeasureRinging(simtree::robots::RunMujocoPull(xml, pull), 0);
}

void Measure(const std::string& name, const simtree::Tree& tree,
             const std::vector<Resolution>& resolutions, const std::vector<int>& branches) {
  const simtree::robots::StepBudget chosen =
      simtree::robots::ChooseStepBudget(tree, simtree::robots::RobotModelOptions{}, {});
  for (const Resolution& resolution : resolutions) {
    simtree::robots::ExportOptions options;
    options.budget.min_steps_per_second = 0;
    options.model.segments_per_branch = resolution.segments;
    options.model.twist = resolution.twist;
    const simtree::robots::RobotModel model = simtree::robots::MakeRobotModel(tree, options);
    const auto xml = std::filesystem::temp_directory_path() / "simtree_budget_accuracy.xml";
    simtree::robots::ExportRobot(tree, options, xml);
    const bool budget = chosen.segments == resolution.segments && chosen.twist == resolution.twist;
    for (int branch : branches) {
      const simtree::Mode& mode = tree.branches[branch].material->modes[0];
      const simtree::robots::Ringing r = PullTip(tree, model, xml, branch);
      std::printf("%s | %d/%s%s | %d | %.3f | %.3f (%+.1f%%) | %.4f | %.4f (%+.1f%%)%s\n",
                  name.c_str(), resolution.segments, simtree::robots::ToString(resolution.twist),
                  budget ? " (budget)" : "", branch, mode.frequency_hz, r.frequency_hz,
                  100 * (r.frequency_hz / mode.frequency_hz - 1), mode.damping_ratio,
                  r.damping_ratio, 100 * (r.damping_ratio / mode.damping_ratio - 1),
                  r.ok ? "" : (" " + r.message).c_str());
      std::fflush(stdout);
    }
    std::filesystem::remove(xml);
  }
}

}  // namespace

int main() {
  simtree::TreeFileOptions read;
  read.legacy_parameters = SIMTREE_SHARED_DATA_DIR "/authors-demo/tree_parameters.txt";
  const simtree::Tree tree01 =
      simtree::ReadTreeFile(SIMTREE_SHARED_DATA_DIR "/authors-demo/tree_model/tree01.txt", read);
  std::printf("tree | segments/twist | branch | f | MuJoCo f | zeta | MuJoCo zeta\n");
  Measure("tree01", tree01,
          {{4, TwistHinges::kBranchesWithKids},
           {2, TwistHinges::kBranchesWithKids},
           {1, TwistHinges::kNone}},
          {6, 7, 8, 1});
  // At 1,000 branches the full resolution steps at ~30/s (hours for these pulls): the budget's
  // resolution and the next finer rung.
  Measure("ternary 1000", bench::TernaryTree(1000),
          {{1, TwistHinges::kBranchesWithKids}, {1, TwistHinges::kNone}}, {1, 2, 3});
  return 0;
}
