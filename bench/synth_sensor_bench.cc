// Virtual Azure Kinect throughput: frames per second of the authors' tree02 (148 branches, about
// 4 m tall) seen from 2.5 m, with the per-frame scene update (a new tree pose) included, on one
// thread (Arg 1) and on every core (Arg 0); and the parts on their own: pose update, rendering
// without shadow rays or marker boxes, primary rays alone (single and in packets), marker boxes.
//
//   build/bin/bench_synth_sensor --benchmark_counters_tabular=true
//
// The default `simtree synth` renders 10 scan views and 450 pull frames, so a frame must stay well
// under ~50 ms for the whole verb to finish in a minute on 2 cores.

#include <benchmark/benchmark.h>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <cmath>
#include <thread>

#include "simtree/core/frames.h"
#include "simtree/core/tree_file.h"
#include "simtree/synth/detail/camera_rig.h"
#include "simtree/synth/detail/rgbd_renderer.h"
#include "simtree/synth/detail/sensor_pose.h"

namespace simtree {
namespace {

Tree BenchTree() {
  Tree tree =
      ReadTreeFile(std::string(SIMTREE_SHARED_DATA_DIR) + "/authors-demo/tree_model/tree02.txt");
  // Eight tape markers, at mid-length of the first thick branches.
  for (const Branch& b : tree.branches) {
    if (tree.markers.size() >= 8) break;
    if (b.nodes[b.nodes.size() / 2].radius < 0.008) continue;
    Marker m;
    m.id = static_cast<int>(tree.markers.size());
    m.branch = b.id;
    m.arc_length = 0.5 * b.Length();
    m.parent = m.id == 0 ? -1 : 0;
    m.position = b.PointAt(m.arc_length);
    tree.markers.push_back(m);
  }
  return tree;
}

// A procedural-size tree: `branches` branches of 7 nodes (a trunk and up to 6 children per
// branch, breadth first), radii from 6 cm down to about 2 mm, spread in a crown 2-4 m up.
Tree LargeTree(int branches) {
  Tree tree;
  tree.branches.reserve(branches);  // `p` below stays valid while children are added
  auto add = [&](int parent, int parent_node, const Eigen::Vector3d& base,
                 const Eigen::Vector3d& direction, double length, double radius) {
    Branch b;
    b.id = tree.size();
    b.parent = parent;
    b.parent_node = parent_node;
    const Eigen::Vector3d d = direction.normalized();
    const Eigen::Vector3d side = d.unitOrthogonal();
    for (int i = 0; i < 7; ++i) {
      const double x = i / 6.0;
      b.nodes.push_back({base + length * (x * d + 0.08 * x * x * side),
                         std::max(0.002, radius * (1.0 - 0.5 * x))});
    }
    tree.branches.push_back(std::move(b));
  };
  add(-1, 0, {0, 0, 0}, {0, 0, 1}, 2.5, 0.06);
  for (int parent = 0; tree.size() < branches; ++parent) {
    const Branch& p = tree.branches[parent];
    const double length = 0.65 * (p.nodes.back().position - p.nodes.front().position).norm();
    for (int c = 0; c < 6 && tree.size() < branches; ++c) {
      const int node = 1 + c;
      const double a = 2.39996 * tree.size();
      const Eigen::Vector3d dir = (p.nodes[6].position - p.nodes[0].position).normalized() +
                                  1.1 * Eigen::Vector3d(std::cos(a), std::sin(a), 0.2);
      add(parent, node, tree.branches[parent].nodes[node].position, dir, length,
          0.6 * tree.branches[parent].nodes[node].radius);
    }
  }
  AssignLevels(tree);
  ComputeFrames(tree);
  return tree;
}

// A sway of the crown that changes every frame: nodes move sideways by up to 5 cm with height.
void Sway(const Tree& tree, int frame, synth::TreePose& pose) {
  const double phase = 2.0 * 3.14159265358979 * frame / 30.0;
  for (const Branch& b : tree.branches) {
    for (size_t i = 0; i < b.nodes.size(); ++i) {
      const Eigen::Vector3d& rest = b.nodes[i].position;
      pose.node(b.id, static_cast<int>(i)) =
          rest + Eigen::Vector3d(0.0125 * rest.z() * std::sin(phase), 0.0, 0.0);
    }
  }
}

struct Fixture {
  Tree tree = BenchTree();
  synth::SensorScene scene{tree, synth::DefaultSceneOptions(tree, 7)};
  synth::SensorModel sensor = synth::SensorModel::AzureKinectNfov();
  Eigen::Isometry3d camera = synth::LookAt({2.5, 0.0, 1.4}, {0.0, 0.0, 2.0});
  synth::TreePose pose{tree};
};

int Threads(const benchmark::State& state) {
  return state.range(0) > 0 ? static_cast<int>(state.range(0)) : tbb::info::default_concurrency();
}

void BM_SensorFrame(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, Threads(state));
  Fixture f;
  int frame = 0;
  for (auto _ : state) {
    Sway(f.tree, frame, f.pose);
    f.scene.SetPose(f.pose);
    synth::RenderResult r =
        synth::RenderRgbd(f.scene, f.sensor, f.camera, {.seed = 1, .frame = frame});
    benchmark::DoNotOptimize(r.image.depth.pixels.data());
    ++frame;
  }
  state.counters["threads"] = Threads(state);
  state.counters["frames_per_s"] =
      benchmark::Counter(state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SensorFrame)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SensorSetPose(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, Threads(state));
  Fixture f;
  int frame = 0;
  for (auto _ : state) {
    Sway(f.tree, frame++, f.pose);
    f.scene.SetPose(f.pose);
  }
  state.counters["nodes"] = f.pose.node_count();
}
BENCHMARK(BM_SensorSetPose)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

// A procedural-size tree (1,500 branches, 10,500 nodes): pose update and a whole frame.
void BM_SensorFrameLargeTree(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, Threads(state));
  const Tree tree = LargeTree(1500);
  synth::SensorScene scene(tree, synth::DefaultSceneOptions(tree, 7));
  synth::TreePose pose(tree);
  const Eigen::Isometry3d camera = synth::LookAt({3.0, 0.0, 1.4}, {0.0, 0.0, 2.2});
  int frame = 0;
  for (auto _ : state) {
    Sway(tree, frame, pose);
    scene.SetPose(pose);
    synth::RenderResult r = synth::RenderRgbd(scene, synth::SensorModel::AzureKinectNfov(), camera,
                                              {.seed = 1, .frame = frame++});
    benchmark::DoNotOptimize(r.image.depth.pixels.data());
  }
  state.counters["nodes"] = pose.node_count();
}
BENCHMARK(BM_SensorFrameLargeTree)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

// Ray casting and depth measurement only: no shadow rays, no marker boxes.
void BM_SensorRenderBare(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, Threads(state));
  Fixture f;
  int frame = 0;
  for (auto _ : state) {
    synth::RenderResult r =
        synth::RenderRgbd(f.scene, f.sensor, f.camera,
                          {.seed = 1, .frame = frame++, .shadows = false, .marker_boxes = false});
    benchmark::DoNotOptimize(r.image.depth.pixels.data());
  }
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * f.sensor.width * f.sensor.height,
                         benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SensorRenderBare)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

// Primary rays only (Embree and the hit decoding), one thread, one rtcIntersect1 per pixel.
void BM_SensorPrimaryRaysSingle(benchmark::State& state) {
  Fixture f;
  const CameraIntrinsics k = f.sensor.Intrinsics();
  const Eigen::Matrix3d r = f.camera.linear();
  const Eigen::Vector3d o = f.camera.translation();
  for (auto _ : state) {
    int hits = 0;
    for (int y = 0; y < k.height; ++y) {
      for (int x = 0; x < k.width; ++x) {
        hits += f.scene.Intersect(o, r * Eigen::Vector3d((x - k.cx) / k.fx, (y - k.cy) / k.fy, 1.0))
                    .hit();
      }
    }
    benchmark::DoNotOptimize(hits);
  }
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * f.sensor.width * f.sensor.height,
                         benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SensorPrimaryRaysSingle)->Unit(benchmark::kMillisecond);

// Primary rays as packets of 16 (what RenderRgbd does): tiles of `rows` x 16 / rows pixels.
void BM_SensorPrimaryRaysPackets(benchmark::State& state) {
  Fixture f;
  const CameraIntrinsics k = f.sensor.Intrinsics();
  const Eigen::Matrix3d r = f.camera.linear();
  const Eigen::Vector3d o = f.camera.translation();
  const int tile = static_cast<int>(state.range(0));
  std::vector<Eigen::Vector3d> dirs(k.width * tile);
  std::vector<synth::SceneHit> hits(dirs.size());
  for (auto _ : state) {
    int count = 0;
    for (int y0 = 0; y0 < k.height; y0 += tile) {
      size_t n = 0;
      for (int x0 = 0; x0 < k.width; x0 += 16 / tile) {
        for (int dy = 0; dy < tile; ++dy) {
          for (int dx = 0; dx < 16 / tile; ++dx) {
            dirs[n++] = r * Eigen::Vector3d((x0 + dx - k.cx) / k.fx, (y0 + dy - k.cy) / k.fy, 1.0);
          }
        }
      }
      f.scene.IntersectCoherent(o, dirs, hits);
      for (const synth::SceneHit& h : hits) count += h.hit();
    }
    benchmark::DoNotOptimize(count);
  }
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * f.sensor.width * f.sensor.height,
                         benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SensorPrimaryRaysPackets)->Arg(1)->Arg(2)->Arg(4)->Unit(benchmark::kMillisecond);

void BM_SensorMarkerBoxes(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, Threads(state));
  Fixture f;
  const synth::RenderResult r =
      synth::RenderRgbd(f.scene, f.sensor, f.camera, {.seed = 1, .frame = 0});
  for (auto _ : state) {
    auto boxes = synth::ComputeMarkerBoxes(f.scene, r.image.intrinsics, f.camera, r.labels);
    benchmark::DoNotOptimize(boxes.data());
  }
  state.counters["markers"] = static_cast<double>(f.tree.markers.size());
}
BENCHMARK(BM_SensorMarkerBoxes)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace simtree

BENCHMARK_MAIN();
