// Frames per second of the marker tracker on one core, frames already in memory (PNG decoding,
// which `track` spreads over threads, is not counted).
//
//   bench_tracking                                    drawn 640x576 frames, 16 markers
//   SIMTREE_BENCH_CAPTURE=/tmp/trk/acer_rubrum_1 bench_tracking   a synth capture's pull stream
//     (its pull/init.json, or init.json beside the capture folder: <capture>.init.json)
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include <benchmark/benchmark.h>

#include "simtree/core/progress.h"
#include "simtree/io/capture.h"
#include "simtree/io/track_init.h"
#include "simtree/tracking/detail/color_model.h"
#include "simtree/tracking/detail/marker_tracker.h"
#include "tracking/drawn_stream.h"

namespace fs = std::filesystem;

namespace simtree::tracking {
namespace {

struct Stream {
  std::vector<RgbdImage> frames;
  TrackInit init;
  double dt = 1.0 / 30.0;
};

// 16 markers on a 4 x 4 grid swinging with different phases, 640 x 576.
Stream DrawnStream() {
  test::DrawnStream s;
  s.intrinsics = CameraIntrinsics{.width = 640,
                                  .height = 576,
                                  .fx = 434.2,
                                  .fy = 434.2,
                                  .cx = 319.5,
                                  .cy = 287.5,
                                  .depth_scale_m = 0.001};
  s.half_length_m = 0.02;
  s.radius_m = 0.008;
  Stream out;
  for (int f = 0; f < 120; ++f) {
    std::vector<Eigen::Vector3d> p;
    for (int m = 0; m < 16; ++m) {
      const double phase = 0.4 * m, t = f / 30.0;
      p.push_back(Eigen::Vector3d(-0.6 + 0.4 * (m % 4) + 0.05 * std::sin(5 * t + phase),
                                  -0.6 + 0.4 * (m / 4), 2.5 + 0.02 * std::cos(5 * t + phase)));
    }
    out.frames.push_back(test::DrawFrame(s, p));
    if (f == 0) {
      for (int m = 0; m < 16; ++m) out.init.markers.push_back({m, s.intrinsics.Project(p[m])});
    }
  }
  return out;
}

Stream CaptureStream(const fs::path& capture) {
  Capture c = OpenCapture(capture);
  Stream out;
  const fs::path init = fs::exists(capture / "pull" / "init.json")
                            ? capture / "pull" / "init.json"
                            : fs::path(capture.string() + ".init.json");
  out.init = ReadTrackInitJson(init);
  for (size_t i = 0; i < std::min<size_t>(c.pull->frames.size(), 300); ++i) {
    out.frames.push_back(LoadPullFrame(*c.pull, i));
  }
  out.dt = 1.0 / c.pull->FrameRate();
  return out;
}

const Stream& TheStream() {
  static const Stream stream = [] {
    const char* capture = std::getenv("SIMTREE_BENCH_CAPTURE");
    return capture ? CaptureStream(capture) : DrawnStream();
  }();
  return stream;
}

void BM_TrackFrames(benchmark::State& state) {
  const Stream& s = TheStream();
  std::vector<int> ids;
  std::vector<Eigen::Vector2d> pixels;
  for (const MarkerPixel& m : s.init.markers) {
    ids.push_back(m.id);
    pixels.push_back(m.pixel);
  }
  const detail::TapeColorModel model =
      detail::FitColorModel(detail::ColorModelFromName("auto"), s.frames[0].color, pixels, 4);
  int64_t frames = 0;
  for (auto _ : state) {
    detail::MarkerTracker tracker(TrackOptions{}, model, s.frames[0].intrinsics, ids, pixels);
    for (const RgbdImage& frame : s.frames) {
      benchmark::DoNotOptimize(tracker.Step(frame, s.dt));
    }
    frames += static_cast<int64_t>(s.frames.size());
  }
  state.counters["frames/s"] =
      benchmark::Counter(static_cast<double>(frames), benchmark::Counter::kIsRate);
  state.counters["markers"] = static_cast<double>(ids.size());
}
BENCHMARK(BM_TrackFrames)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace simtree::tracking

BENCHMARK_MAIN();
