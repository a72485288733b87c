// MuJoCo steps per second of an exported tree against its branch count: a regular ternary tree
// (every branch 3 nodes, 3 children at its middle and tip) of 100 to 1,000 branches, exported
// as MJCF (segments per branch and twist hinges as the arguments say), stepped from rest with a
// force on one tip. The bar: >= 1,000 steps per second at 1,000 branches.
//   build/bin/bench_robots --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <filesystem>

#include <Eigen/Geometry>

#include "simtree/core/frames.h"
#include "simtree/robots/export_robot.h"

namespace {

simtree::Tree TernaryTree(int branch_count) {
  simtree::Tree tree;
  simtree::Branch trunk;
  trunk.nodes = {{Eigen::Vector3d(0, 0, 0), 0.08},
                 {Eigen::Vector3d(0, 0, 0.8), 0.07},
                 {Eigen::Vector3d(0, 0, 1.6), 0.06}};
  tree.branches.push_back(trunk);
  for (int id = 0; static_cast<int>(tree.branches.size()) < branch_count; ++id) {
    const simtree::Branch parent = tree.branches[id];
    const Eigen::Vector3d axis = (parent.tip().position - parent.base().position).normalized();
    const double length = (parent.tip().position - parent.base().position).norm() * 0.7;
    for (int k = 0; k < 3 && static_cast<int>(tree.branches.size()) < branch_count; ++k) {
      const int node = k == 0 ? 1 : 2;
      const double heading = 2.0944 * k + 0.7 * id;
      const Eigen::Vector3d side = axis.unitOrthogonal() * std::cos(heading) +
                                   axis.cross(axis.unitOrthogonal()) * std::sin(heading);
      const Eigen::Vector3d direction = (axis + 0.9 * side).normalized();
      const Eigen::Vector3d base = parent.nodes[node].position;
      const double radius = parent.nodes[node].radius * 0.6;
      simtree::Branch child;
      child.id = static_cast<int>(tree.branches.size());
      child.parent = id;
      child.parent_node = node;
      child.nodes = {{base, radius},
                     {base + 0.5 * length * direction, 0.8 * radius},
                     {base + length * direction, 0.6 * radius}};
      tree.branches.push_back(child);
    }
  }
  simtree::AssignLevels(tree);
  simtree::ComputeFrames(tree);
  for (simtree::Branch& b : tree.branches) {
    b.material = simtree::Material::FromFrequencyDampingStiffness(
        b.is_trunk() ? 3.0 : 1.2, 0.04, b.is_trunk() ? 5000.0 : 50.0,
        simtree::MaterialSource::kAssumed);
  }
  return tree;
}

void BM_MujocoStep(benchmark::State& state) {
  const simtree::Tree tree = TernaryTree(static_cast<int>(state.range(0)));
  const auto path = std::filesystem::temp_directory_path() /
                    ("simtree_bench_robots_" + std::to_string(state.range(0)) + ".xml");
  simtree::robots::ExportOptions options;
  options.model.segments_per_branch = static_cast<int>(state.range(1));
  if (state.range(2) == 0) options.model.twist = simtree::robots::TwistHinges::kNone;
  const simtree::robots::ExportResult exported = simtree::robots::ExportRobot(tree, options, path);
  char error[1000] = "";
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof(error));
  if (!m) {
    state.SkipWithError(error);
    return;
  }
  mjData* d = mj_makeData(m);
  d->xfrc_applied[6 * (m->nbody - 1) + 0] = 5.0;
  for (auto _ : state) mj_step(m, d);
  state.counters["branches"] = tree.size();
  state.counters["bodies"] = exported.bodies;
  state.counters["dofs"] = m->nv;
  state.counters["dt_ms"] = 1e3 * m->opt.timestep;
  state.counters["unstable"] = d->warning[mjWARN_BADQACC].number;
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  mj_deleteData(d);
  mj_deleteModel(m);
  std::filesystem::remove(path);
}
// Arguments: branches, segments per branch, twist hinges (1 auto, 0 none).
BENCHMARK(BM_MujocoStep)
    ->Args({100, 4, 1})
    ->Args({1000, 4, 1})
    ->Args({1000, 1, 1})
    ->Args({1000, 1, 0})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
BENCHMARK_MAIN();
