// The FEM oracle's cost on real trees: assembly, the 60 lowest modes, 15 s of a pull test by
// Newmark at 1/600 s (direct: the whole system; modal: the modes plus the static residual, 450
// camera frames), and the whole oracle as `synth` runs it (model, modes, pull, modal truth).
//
//   build/bin/bench_synth_fem --benchmark_counters_tabular=true
//
// Trees: the authors' tree01 and tree02 as their files mesh them (5 cm segments), and tree01
// with every element split to 1.25 cm and 0.625 cm, which stand in for the 5,000-12,000-node
// procedural trees of `synth` (the cost follows the node count, not the shape).

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "simtree/core/progress.h"
#include "simtree/core/tree_file.h"
#include "simtree/synth/detail/fem_modes.h"
#include "simtree/synth/detail/fem_response.h"
#include "simtree/synth/detail/fem_truth.h"

namespace simtree {
namespace {

struct BenchCase {
  const char* file;
  double max_element_length_m;
};
// Arg index -> tree and mesh.
const BenchCase kCases[] = {
    {"tree01.txt", 0.1}, {"tree02.txt", 0.1}, {"tree01.txt", 0.0125}, {"tree01.txt", 0.00625}};

const Tree& CachedTree(const std::string& file) {
  static std::map<std::string, Tree> cache;
  auto it = cache.find(file);
  if (it == cache.end()) {
    Tree tree =
        ReadTreeFile(std::string(SIMTREE_SHARED_DATA_DIR) + "/authors-demo/tree_model/" + file);
    // Markers as synth would tape them: the trunk at a third of its length, then the middle of
    // every first-level branch, linked to the trunk marker.
    tree.markers.push_back({0, "M0", 0, tree.trunk().Length() / 3, -1, {}});
    for (const Branch& b : tree.branches) {
      if (b.level != 1) continue;
      const int id = static_cast<int>(tree.markers.size());
      tree.markers.push_back({id, fmt::format("M{}", id), b.id, b.Length() / 2, 0, {}});
    }
    for (Marker& m : tree.markers) m.position = tree.branches[m.branch].PointAt(m.arc_length);
    it = cache.emplace(file, std::move(tree)).first;
  }
  return it->second;
}

synth::WoodProperties BenchWood() {
  synth::WoodProperties wood;
  wood.SetRayleighFromRatios(1.0, 0.04, 10.0, 0.03);
  return wood;
}

const synth::FemModel& CachedModel(int index) {
  static std::map<int, synth::FemModel> cache;
  auto it = cache.find(index);
  if (it == cache.end()) {
    const BenchCase& c = kCases[index];
    it = cache
             .emplace(index, synth::FemModel(CachedTree(c.file), BenchWood(),
                                             {.max_element_length_m = c.max_element_length_m}))
             .first;
  }
  return it->second;
}

const synth::ModalBasis& CachedModes(int index) {
  static std::map<int, synth::ModalBasis> cache;
  auto it = cache.find(index);
  if (it == cache.end()) it = cache.emplace(index, synth::ComputeModes(CachedModel(index))).first;
  return it->second;
}

PullLoad BenchPull(const Tree& tree) {
  // A first-level branch pulled at two thirds of its length towards a stake 2 m out.
  int branch = 1;
  for (const Branch& b : tree.branches) {
    if (b.level == 1) {
      branch = b.id;
      break;
    }
  }
  PullLoad pull;
  pull.branch = branch;
  pull.arc_length = 2.0 / 3.0 * tree.branches[branch].Length();
  pull.attach_point = tree.branches[branch].PointAt(pull.arc_length);
  pull.anchor = pull.attach_point + Eigen::Vector3d(2.0, 0.5, -1.0);
  pull.force_n = 40.0;
  pull.ramp_start_s = 0.5;
  pull.hold_start_s = 2.5;
  pull.release_s = 4.5;
  pull.duration_s = 15.0;
  return pull;
}

std::vector<double> FrameTimes(double duration, double fps) {
  std::vector<double> t;
  for (int i = 0; i < static_cast<int>(duration * fps); ++i) t.push_back(i / fps);
  return t;
}

void SetCounters(benchmark::State& state, const synth::FemModel& model) {
  state.counters["nodes"] = model.node_count();
  state.counters["dof"] = model.dof_count();
  const BenchCase& c = kCases[state.range(0)];
  state.SetLabel(fmt::format("{} h={}", c.file, c.max_element_length_m));
}

void BM_Assemble(benchmark::State& state) {
  Progress::SetEnabled(false);
  const BenchCase& c = kCases[state.range(0)];
  const Tree& tree = CachedTree(c.file);
  for (auto _ : state) {
    synth::FemModel model(tree, BenchWood(), {.max_element_length_m = c.max_element_length_m});
    benchmark::DoNotOptimize(model.stiffness().nonZeros());
  }
  SetCounters(state, CachedModel(static_cast<int>(state.range(0))));
}

void BM_Modes60(benchmark::State& state) {
  Progress::SetEnabled(false);
  const synth::FemModel& model = CachedModel(static_cast<int>(state.range(0)));
  synth::ModalBasis modes;
  for (auto _ : state) {
    modes = synth::ComputeModes(model, {.count = 60});
    benchmark::DoNotOptimize(modes.omega.data());
  }
  SetCounters(state, model);
  state.counters["f1_hz"] = modes.frequency_hz[0];
  state.counters["f60_hz"] = modes.frequency_hz[modes.count() - 1];
}

// 15 s of the pull test, 450 frames at 30 fps, at 1/600 s.
void BM_PullDirect15s(benchmark::State& state) {
  Progress::SetEnabled(false);
  const synth::FemModel& model = CachedModel(static_cast<int>(state.range(0)));
  const PullLoad pull = BenchPull(model.tree());
  const std::vector<double> frames = FrameTimes(pull.duration_s, 30.0);
  for (auto _ : state) {
    const synth::PullResult r = synth::IntegratePull(
        model, pull, frames, {},
        [](int, double, const synth::FemState& s) { benchmark::DoNotOptimize(s.x.data()); });
    state.counters["steps"] = static_cast<double>(r.run.steps);
  }
  SetCounters(state, model);
}

void BM_PullModal15s(benchmark::State& state) {
  Progress::SetEnabled(false);
  const synth::FemModel& model = CachedModel(static_cast<int>(state.range(0)));
  const synth::ModalBasis& modes = CachedModes(static_cast<int>(state.range(0)));
  const PullLoad pull = BenchPull(model.tree());
  const std::vector<double> frames = FrameTimes(pull.duration_s, 30.0);
  for (auto _ : state) {
    // What synth needs per frame: the pose of the tree.
    const synth::PullResult r =
        synth::IntegratePull(model, modes, pull, frames, {.sample_rates = false},
                             [&](int, double, const synth::FemState& s) {
                               const synth::TreePose pose = model.Pose(s.x);
                               benchmark::DoNotOptimize(pose.positions().data());
                             });
    state.counters["steps"] = static_cast<double>(r.run.steps);
  }
  SetCounters(state, model);
}

// Everything synth asks of the oracle for one pull scene.
void BM_WholeOracle(benchmark::State& state) {
  Progress::SetEnabled(false);
  const BenchCase& c = kCases[state.range(0)];
  const Tree& tree = CachedTree(c.file);
  const PullLoad pull = BenchPull(tree);
  const std::vector<double> frames = FrameTimes(pull.duration_s, 30.0);
  for (auto _ : state) {
    const synth::FemModel model(tree, BenchWood(),
                                {.max_element_length_m = c.max_element_length_m});
    const synth::ModalBasis modes =
        synth::ComputeModes(model, {.count = 60, .cover_frequency_hz = 20.0});
    const synth::PullResult run =
        synth::IntegratePull(model, modes, pull, frames, {.sample_rates = false},
                             [&](int, double, const synth::FemState& s) {
                               const synth::TreePose pose = model.Pose(s.x);
                               benchmark::DoNotOptimize(pose.positions().data());
                             });
    const ModalTruth truth = synth::ComputeModalTruth(model, modes, tree, run.release_state);
    benchmark::DoNotOptimize(truth.links.data());
    state.counters["modes"] = modes.count();
  }
  SetCounters(state, CachedModel(static_cast<int>(state.range(0))));
}

BENCHMARK(BM_Assemble)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Modes60)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_PullDirect15s)->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_PullModal15s)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_WholeOracle)->DenseRange(0, 3)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace simtree

BENCHMARK_MAIN();
