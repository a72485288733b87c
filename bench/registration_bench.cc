// Per-stage costs of registration on the stand-in scene (the authors' tree01 seen from a ring of
// cameras, tests/registration/stand_in_scene.h): preparing a view (normals, trunk, cylinder,
// medial projection, L1-medial skeleton, FPFH), and registering a pair 36 and 180 degrees apart.
// The side-by-side comparison with the peers is registration_compare.

#include <benchmark/benchmark.h>
#include <oneapi/tbb/global_control.h>

#include "registration/stand_in_scene.h"
#include "simtree/preprocessing/depth_to_cloud.h"
#include "simtree/registration/detail/pairwise.h"

namespace simtree {
namespace {

struct Bench {
  std::vector<preprocessing::PreprocessResult> preprocessed;
  std::vector<registration::RegistrationView> views;
};

const Bench& Scene() {
  static const Bench bench = [] {
    Bench b;
    const Tree tree = test::LoadDemoTree(std::string(SIMTREE_SHARED_DATA_DIR) +
                                         "/authors-demo/tree_model/tree01.txt");
    test::StandInOptions options;
    options.seed = 1;
    Eigen::Vector3d lo, hi;
    tree.Bounds(&lo, &hi);
    const auto poses = test::StandInPoses(hi.z(), options);
    for (size_t v = 0; v < poses.size(); ++v) {
      const RgbdImage image =
          test::RenderStandInView(tree, poses[v].world_from_camera, options, 1000 + v);
      b.preprocessed.push_back(preprocessing::PreprocessView(preprocessing::DepthToCloud(image)));
      b.views.push_back(registration::PrepareView(poses[v].name, b.preprocessed.back()));
    }
    return b;
  }();
  return bench;
}

void BM_PrepareView(benchmark::State& state) {
  oneapi::tbb::global_control threads(oneapi::tbb::global_control::max_allowed_parallelism,
                                      state.range(0));
  const auto& pre = Scene().preprocessed[0];
  for (auto _ : state) benchmark::DoNotOptimize(registration::PrepareView("view", pre));
  state.counters["points"] = static_cast<double>(pre.cloud.points_.size());
}
BENCHMARK(BM_PrepareView)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RegisterPair(benchmark::State& state) {
  oneapi::tbb::global_control threads(oneapi::tbb::global_control::max_allowed_parallelism, 2);
  const auto& views = Scene().views;
  const int gap = static_cast<int>(state.range(0));  // in steps of 36 degrees
  const registration::PairOptions options;
  for (auto _ : state)
    benchmark::DoNotOptimize(registration::RegisterPair(views[gap], views[0], options));
  state.SetLabel(std::to_string(36 * gap) + " deg apart");
}
BENCHMARK(BM_RegisterPair)->Arg(1)->Arg(5)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Preprocess(benchmark::State& state) {
  const Tree tree = test::LoadDemoTree(std::string(SIMTREE_SHARED_DATA_DIR) +
                                       "/authors-demo/tree_model/tree01.txt");
  test::StandInOptions options;
  const auto poses = test::StandInPoses(3.0, options);
  const auto cloud = preprocessing::DepthToCloud(
      test::RenderStandInView(tree, poses[0].world_from_camera, options, 1));
  for (auto _ : state) benchmark::DoNotOptimize(preprocessing::PreprocessView(cloud));
  state.counters["raw_points"] = static_cast<double>(cloud.points_.size());
}
BENCHMARK(BM_Preprocess)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace simtree

BENCHMARK_MAIN();
