// Frame time of the interactive viewer on the authors' tree02, with and without leaves, with the
// simulation running (a held rope pull and a 5 m/s turbulent wind): the real window, scene, panel
// and buffer swap, under Xvfb's software OpenGL (Mesa llvmpipe). Starts Xvfb itself when there is
// no display. The leaves are drawn as the viewer draws them (the leaf model simplified to 1 % of
// its length, scene_renderer.h) and as the authors' mesh (authors_mesh:1), to show what that buys.
// docs/benchmarks.md, "Viewer and renderer", keeps the figures.
//
//   build-bench/bin/bench_viewer --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <memory>

#include "simtree/core/tree_file.h"
#include "simtree/viewer/demo_materials.h"
#include "simtree/viewer/scene_assets.h"
#include "simtree/viewer/view.h"
#include "simtree/viewer/xvfb.h"

namespace simtree {
namespace {

// CPU time of the whole process (every llvmpipe thread included), seconds.
double ProcessCpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
         1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

const std::filesystem::path kTree02 =
    std::filesystem::path(SIMTREE_SHARED_DATA_DIR) / "authors-demo/tree_model/tree02.txt";

void BM_ViewerFrameTree02(benchmark::State& state) {
  static std::unique_ptr<viewer::ScopedXvfb> xvfb;
  if (!viewer::HasDisplay() && !xvfb) xvfb = std::make_unique<viewer::ScopedXvfb>(1280, 800);
  const bool leaves = state.range(0) != 0;
  const bool authors_mesh = state.range(1) != 0;  // the leaf model as shipped, not simplified
  Tree tree = ReadTreeFile(kTree02);
  viewer::FillMissingMaterials(tree);
  viewer::FoliageSource foliage;
  foliage.leaves = leaves ? "auto" : "none";
  const viewer::SceneAssets assets = viewer::LoadSceneAssets(tree, kTree02, foliage);

  viewer::ViewerOptions options;
  options.width = 1280;
  options.height = 800;
  options.fixed_step = true;
  options.fps = 30.0;
  if (authors_mesh) {
    options.scene.leaf_detail.tolerance = 0.0;
    options.scene.petiole_sides = 4;
  }
  options.dynamics.wind.enabled = true;
  options.dynamics.wind.mean_speed_mps = 5.0;
  dynamics::PullSchedule pull;
  pull.rope = {.branch = 20, .arc_length = -1, .anchor = {3, 0, 0}, .force_n = 150};
  pull.hold_s = 0.5;
  pull.release_s = 1e9;  // held for the whole run
  options.pull = pull;
  viewer::Viewer viewer(tree, assets, options);
  for (int i = 0; i < 10; ++i) viewer.Frame();  // warm up: shader compilation, first uploads

  const double cpu_start = ProcessCpuSeconds();
  for (auto _ : state) viewer.Frame();
  const double cpu = ProcessCpuSeconds() - cpu_start;

  const viewer::ViewerStats& stats = viewer.stats();
  state.counters["triangles"] = static_cast<double>(stats.triangles);
  state.counters["leaves"] = static_cast<double>(assets.leaves.size());
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["simulate_ms"] = stats.mean_simulate_ms;
  // The work of a frame on all threads: with the machine to itself, wall time is at least this
  // over the cores llvmpipe uses.
  state.counters["process_cpu_ms"] = 1000.0 * cpu / static_cast<double>(state.iterations());
  state.SetLabel(stats.renderer);
}
BENCHMARK(BM_ViewerFrameTree02)
    ->ArgNames({"leaves", "authors_mesh"})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Args({0, 0})
    ->Iterations(200)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace simtree

BENCHMARK_MAIN();
