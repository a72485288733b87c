// Core data model throughput: tube meshing and the tree file formats, on the authors' tree02
// and on a synthetic tree of N branches.

#include <benchmark/benchmark.h>

#include <filesystem>

#include "simtree/core/frames.h"
#include "simtree/core/legacy_format.h"
#include "simtree/core/tree_json.h"
#include "simtree/core/tube_mesh.h"

namespace simtree {
namespace {

// A comb: a trunk with `branches - 1` straight 20-node children.
Tree Comb(int branches) {
  Tree tree;
  Branch trunk;
  const int trunk_nodes = std::max(2, branches);
  for (int i = 0; i < trunk_nodes; ++i) trunk.nodes.push_back({{0, 0, 0.01 * i}, 0.2});
  tree.branches.push_back(trunk);
  for (int b = 1; b < branches; ++b) {
    Branch child;
    child.id = b;
    child.parent = 0;
    child.parent_node = b;
    const Eigen::Vector3d base = tree.branches[0].nodes[b].position;
    const Eigen::Vector3d dir(std::cos(b * 2.4), std::sin(b * 2.4), 0.5);
    for (int i = 0; i < 20; ++i) child.nodes.push_back({base + dir * 0.05 * i, 0.02});
    tree.branches.push_back(child);
  }
  AssignLevels(tree);
  ComputeFrames(tree);
  return tree;
}

void BM_TubeMesh(benchmark::State& state) {
  const Tree tree = Comb(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(BuildTubeMesh(tree));
  state.counters["nodes/s"] =
      benchmark::Counter(tree.NodeCount(), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_TubeMesh)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

void BM_TreeJsonWriteRead(benchmark::State& state) {
  const Tree tree = Comb(static_cast<int>(state.range(0)));
  const auto path = std::filesystem::temp_directory_path() / "simtree_bench_tree.json";
  for (auto _ : state) {
    WriteTreeJson(tree, path);
    benchmark::DoNotOptimize(ReadTreeJson(path));
  }
  std::filesystem::remove(path);
  state.counters["nodes/s"] =
      benchmark::Counter(tree.NodeCount(), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_TreeJsonWriteRead)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

void BM_LegacyRead(benchmark::State& state) {
  const std::filesystem::path path =
      std::filesystem::path(SIMTREE_SHARED_DATA_DIR) / "authors-demo/tree_model/tree02.txt";
  for (auto _ : state) benchmark::DoNotOptimize(ReadLegacyTree(path));
}
BENCHMARK(BM_LegacyRead)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace simtree

BENCHMARK_MAIN();
