// MuJoCo steps per second of an exported tree against its branch count: a regular ternary tree
// (robots_ternary_tree.h) of 100 to 1,000 branches and the authors' tree01, exported as MJCF
// (at the defaults, where the step budget chooses, or at the segments per branch and twist
// hinges the arguments say, with no budget), stepped from rest with a push of twice its weight
// on the last twig, with MuJoCo's phase timers (the share of a step in each phase), the step
// budget's estimate (est_steps_per_s) and what it is estimated from (dofs, depth_sq_sum). The
// issue's bar: >= 1,000 steps per second at 1,000 branches.
//   build/bin/bench_robots --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <chrono>
#include <cmath>
#include <filesystem>

#include <Eigen/Geometry>

#include "robots_ternary_tree.h"
#include "simtree/core/frames.h"
#include "simtree/core/tree_file.h"
#include "simtree/robots/export_robot.h"

namespace {

// MuJoCo's phase timers read this clock (ms).
mjtNum ClockMs() {
  return std::chrono::duration<double, std::milli>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Where a step's time goes: each phase's share of mj_step, from MuJoCo's own timers.
void CountPhases(const mjData* d, benchmark::State& state) {
  const double step = d->timer[mjTIMER_STEP].duration;
  if (step <= 0) return;
  const std::pair<const char*, int> phases[] = {
      {"pct_kinematics", mjTIMER_POS_KINEMATICS}, {"pct_inertia", mjTIMER_POS_INERTIA},
      {"pct_collision", mjTIMER_POS_COLLISION},   {"pct_velocity", mjTIMER_VELOCITY},
      {"pct_acceleration", mjTIMER_ACCELERATION}, {"pct_constraint", mjTIMER_CONSTRAINT}};
  for (const auto& [name, timer] : phases)
    state.counters[name] = 100 * d->timer[timer].duration / step;
}

// What the mass-matrix factorisation walks: per dof, the dofs on its path to the root (itself
// counted), summed and summed squared.
void CountDepths(const mjModel* m, benchmark::State& state) {
  double sum = 0, sum_sq = 0;
  for (int k = 0; k < m->nv; ++k) {
    int depth = 0;
    for (int i = k; i >= 0; i = m->dof_parentid[i]) ++depth;
    sum += depth;
    sum_sq += static_cast<double>(depth) * depth;
  }
  state.counters["depth_sum"] = sum;
  state.counters["depth_sq_sum"] = sum_sq;
}

void StepExported(const simtree::Tree& tree, const simtree::robots::ExportOptions& options,
                  const std::string& name, benchmark::State& state) {
  mjcb_time = ClockMs;
  const auto path = std::filesystem::temp_directory_path() / ("simtree_bench_" + name + ".xml");
  const simtree::robots::ExportResult exported = simtree::robots::ExportRobot(tree, options, path);
  char error[1000] = "";
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
  if (!m) {
    state.SkipWithError(error);
    return;
  }
  mjData* d = mj_makeData(m);
  d->xfrc_applied[6 * (m->nbody - 1) + 0] = 2.0 * 9.81 * m->body_mass[m->nbody - 1];
  for (auto _ : state) mj_step(m, d);
  state.counters["branches"] = tree.size();
  state.counters["bodies"] = exported.bodies;
  state.counters["segments"] = exported.segments_per_branch;
  state.counters["twist"] = exported.budget.twist != simtree::robots::TwistHinges::kNone;
  state.counters["dofs"] = m->nv;
  state.counters["dt_ms"] = 1e3 * m->opt.timestep;
  state.counters["unstable"] = d->warning[mjWARN_BADQACC].number;
  CountPhases(d, state);
  CountDepths(m, state);
  state.counters["est_steps_per_s"] = exported.budget.cost.steps_per_second;
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  mj_deleteData(d);
  mj_deleteModel(m);
  std::filesystem::remove(path);
}

void BM_MujocoStep(benchmark::State& state) {
  simtree::robots::ExportOptions options;
  options.budget.min_steps_per_second = 0;  // exactly as asked
  options.model.segments_per_branch = static_cast<int>(state.range(1));
  if (state.range(2) == 0) options.model.twist = simtree::robots::TwistHinges::kNone;
  options.model.collidable = state.range(3) != 0;
  StepExported(bench::TernaryTree(static_cast<int>(state.range(0))), options,
               "robots_" + std::to_string(state.range(0)), state);
}

// At the export's defaults: the step budget chooses the resolution (counters segments, twist).
void BM_MujocoStepDefaults(benchmark::State& state) {
  StepExported(bench::TernaryTree(static_cast<int>(state.range(0))), {},
               "robots_defaults_" + std::to_string(state.range(0)), state);
}

// The authors' tree01 (95 branches) at the export's defaults (range 0 = 1) or at the given
// segments per branch (range 0) and twist (range 1).
void BM_MujocoStepTree01(benchmark::State& state) {
  simtree::TreeFileOptions read;
  read.legacy_parameters = SIMTREE_SHARED_DATA_DIR "/authors-demo/tree_parameters.txt";
  const simtree::Tree tree =
      simtree::ReadTreeFile(SIMTREE_SHARED_DATA_DIR "/authors-demo/tree_model/tree01.txt", read);
  simtree::robots::ExportOptions options;
  options.budget.min_steps_per_second = 0;  // exactly as asked
  options.model.segments_per_branch = static_cast<int>(state.range(0));
  if (state.range(1) == 0) options.model.twist = simtree::robots::TwistHinges::kNone;
  StepExported(tree, options, "robots_tree01", state);
}
// Arguments: branches, segments per branch, twist hinges (1 auto, 0 none), --collidable (1) or
// not (0).
BENCHMARK(BM_MujocoStep)
    ->Args({100, 4, 1, 0})
    ->Args({300, 4, 1, 0})
    ->Args({300, 2, 1, 0})
    ->Args({1000, 4, 1, 0})
    ->Args({1000, 3, 1, 0})
    ->Args({1000, 2, 1, 0})
    ->Args({1000, 2, 0, 0})
    ->Args({1000, 1, 1, 1})
    ->Args({1000, 1, 1, 0})
    ->Args({1000, 1, 0, 1})
    ->Args({1000, 1, 0, 0})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MujocoStepDefaults)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMicrosecond);
// Arguments: segments per branch, twist hinges (1 auto, 0 none).
BENCHMARK(BM_MujocoStepTree01)
    ->Args({4, 1})
    ->Args({2, 1})
    ->Args({1, 0})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
BENCHMARK_MAIN();
