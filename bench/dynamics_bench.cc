// Dynamics throughput: simulated steps per second and node updates per second of TreeDynamics
// against branch count (100 ... 100,000 branches of 20 nodes), on one thread and on all, plus the
// memory-bandwidth ceiling of the node pass measured in the same run.
//
//   build-bench/bin/bench_dynamics --benchmark_counters_tabular=true
//
// The trees are synthetic and deterministic: every branch carries up to 8 children spread along
// it, breadth first, so 100,000 branches make 6 levels, like a large real crown.

#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstring>
#include <map>
#include <thread>
#include <vector>

#include "simtree/core/frames.h"
#include "simtree/dynamics/tree_dynamics.h"

namespace simtree {
namespace {

constexpr int kNodesPerBranch = 20;

Tree BenchTree(int branches) {
  Tree tree;
  tree.branches.reserve(branches);
  auto add = [&](int parent, int parent_node, const Eigen::Vector3d& base,
                 const Eigen::Vector3d& direction, double length, double radius) {
    Branch b;
    b.id = tree.size();
    b.parent = parent;
    b.parent_node = parent_node;
    const Eigen::Vector3d d = direction.normalized();
    // A gentle curve so twist and bending both show.
    const Eigen::Vector3d side = d.unitOrthogonal();
    for (int i = 0; i < kNodesPerBranch; ++i) {
      const double x = static_cast<double>(i) / (kNodesPerBranch - 1);
      b.nodes.push_back({base + length * (x * d + 0.05 * x * x * side), radius * (1.0 - 0.6 * x)});
    }
    tree.branches.push_back(std::move(b));
  };
  add(-1, 0, {0, 0, 0}, {0, 0, 1}, 6.0, 0.3);
  for (int parent = 0; tree.size() < branches; ++parent) {
    const Branch& p = tree.branches[parent];
    const double length = 0.6 * p.Length();
    for (int c = 0; c < 8 && tree.size() < branches; ++c) {
      const int node = 4 + 2 * c;
      const double a = 2.39996 * tree.size();
      const Eigen::Vector3d dir =
          BranchAxis(p) + 1.2 * Eigen::Vector3d(std::cos(a), std::sin(a), 0.3);
      add(parent, node, tree.branches[parent].nodes[node].position, dir, length,
          0.5 * tree.branches[parent].nodes[node].radius);
    }
  }
  AssignLevels(tree);
  ComputeFrames(tree);
  for (Branch& b : tree.branches) {
    const double f = 3.0 / (1.0 + 0.4 * b.level);
    b.material = Material::FromFrequencyDampingStiffness(f, 0.03, 30000.0 / std::pow(2.5, b.level),
                                                         MaterialSource::kDefault);
  }
  return tree;
}

const Tree& CachedTree(int branches) {
  static std::map<int, Tree> cache;
  auto it = cache.find(branches);
  if (it == cache.end()) it = cache.emplace(branches, BenchTree(branches)).first;
  return it->second;
}

// Args: branches, threads (0 = all), wind (0/1).
void BM_Step(benchmark::State& state) {
  const Tree& tree = CachedTree(static_cast<int>(state.range(0)));
  dynamics::DynamicsOptions options;
  options.max_threads = static_cast<int>(state.range(1));
  options.wind.enabled = state.range(2) != 0;
  options.wind.mean_speed_mps = 8.0;
  dynamics::TreeDynamics sim(tree, options);
  // A pull test: a rope on a first-level branch, held.
  dynamics::Rope rope;
  rope.branch = std::min(1, tree.size() - 1);
  rope.anchor = tree.branches[rope.branch].tip().position + Eigen::Vector3d(0, 0, -5);
  rope.force_n = 200.0;
  sim.AttachRope(rope);
  sim.Advance(1.0, 1.0 / 60);
  for (auto _ : state) {
    sim.Step(1.0 / 60);
    benchmark::DoNotOptimize(sim.node_positions().data());
  }
  state.counters["branches"] = tree.size();
  state.counters["nodes"] = tree.NodeCount();
  state.counters["steps/s"] = benchmark::Counter(1, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["node_updates/s"] =
      benchmark::Counter(tree.NodeCount(), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["threads"] = options.max_threads > 0
                                  ? options.max_threads
                                  : static_cast<int>(std::thread::hardware_concurrency());
}

void StepArgs(benchmark::internal::Benchmark* b) {
  for (int branches : {100, 1000, 10000, 100000}) {
    for (int threads : {1, 0}) b->Args({branches, threads, 0});
  }
  b->Args({100000, 0, 1});
}
BENCHMARK(BM_Step)->Apply(StepArgs)->Unit(benchmark::kMillisecond)->UseRealTime();

// The ceiling: stream the node pass's bytes (6 floats read, 3 written per node) with nothing to
// compute, on one thread.
void BM_NodeBandwidthCeiling(benchmark::State& state) {
  const size_t nodes = static_cast<size_t>(state.range(0)) * kNodesPerBranch;
  std::vector<float> in(6 * nodes, 1.0f), out(3 * nodes, 0.0f);
  for (auto _ : state) {
    const float* a = in.data();
    float* o = out.data();
    for (size_t i = 0; i < nodes; ++i) {
      o[3 * i + 0] = a[i] + a[nodes + i];
      o[3 * i + 1] = a[2 * nodes + i] + a[3 * nodes + i];
      o[3 * i + 2] = a[4 * nodes + i] + a[5 * nodes + i];
    }
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.counters["nodes"] = static_cast<double>(nodes);
  state.counters["node_updates/s"] =
      benchmark::Counter(static_cast<double>(nodes), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_NodeBandwidthCeiling)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace simtree

BENCHMARK_MAIN();
