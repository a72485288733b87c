// Reading and registering Azure Kinect captures (docs/benchmarks.md, "Azure Kinect recordings"):
// the real k4arecorder file's one capture (MJPEG 1280x720 colour, 640x576 depth), opened and
// decoded per iteration, and its registration into the undistorted colour camera.

#include <filesystem>
#include <optional>

#include <benchmark/benchmark.h>

#include "simtree/io/azure_kinect.h"

namespace {

using simtree::AzureCapture;
using simtree::AzureKinectReader;
using simtree::AzureReaderOptions;
using simtree::AzureRegistration;

std::filesystem::path Recording() {
  return std::filesystem::path(SIMTREE_SHARED_DATA_DIR) / "azure-kinect/pyk4a_recording.mkv";
}

// Open (headers, calibration) + one capture decoded: the cost of a frame plus the open.
void BM_AzureOpenAndDecode(benchmark::State& state) {
  AzureReaderOptions options;
  options.read_color = state.range(0) != 0;
  for (auto _ : state) {
    AzureKinectReader reader(Recording(), options);
    std::optional<AzureCapture> capture = reader.Next();
    benchmark::DoNotOptimize(capture);
  }
  state.SetLabel(options.read_color ? "colour MJPEG + depth" : "depth only");
}
BENCHMARK(BM_AzureOpenAndDecode)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

// Open only: what BM_AzureOpenAndDecode pays besides decoding.
void BM_AzureOpen(benchmark::State& state) {
  for (auto _ : state) {
    AzureKinectReader reader(Recording());
    benchmark::DoNotOptimize(reader.calibration());
  }
}
BENCHMARK(BM_AzureOpen)->Unit(benchmark::kMillisecond);

// The per-recording set-up: undistortion map and depth pixel rays.
void BM_AzureRegistrationSetUp(benchmark::State& state) {
  AzureKinectReader reader(Recording());
  for (auto _ : state) {
    AzureRegistration registration(reader.calibration());
    benchmark::DoNotOptimize(registration.color_pinhole());
  }
}
BENCHMARK(BM_AzureRegistrationSetUp)->Unit(benchmark::kMillisecond);

// A 30-capture recording of the real capture's frames at 30 fps (MJPEG re-encoded by libav),
// written once, so a stream's per-frame cost is measured without the open.
std::filesystem::path StreamRecording() {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "simtree_bench_azure_stream.mkv";
  if (std::filesystem::exists(path)) return path;
  AzureKinectReader reader(Recording());
  AzureCapture capture = *reader.Next();
  simtree::AzureWriterOptions options;
  options.color_width = capture.color->width;
  options.color_height = capture.color->height;
  options.depth_width = capture.depth->width;
  options.depth_height = capture.depth->height;
  options.calibration_json = reader.calibration_json();
  simtree::AzureKinectWriter writer(path, options);
  for (int i = 0; i < 30; ++i) {
    capture.color_timestamp_us = capture.depth_timestamp_us = i * 33000;
    writer.Write(capture);
  }
  writer.Close();
  return path;
}

// Every capture of a 30-capture stream: items/s is decoded captures per second.
void BM_AzureStream(benchmark::State& state) {
  const std::filesystem::path path = StreamRecording();
  AzureReaderOptions options;
  options.read_color = state.range(0) != 0;
  int64_t captures = 0;
  for (auto _ : state) {
    AzureKinectReader reader(path, options);
    while (std::optional<AzureCapture> capture = reader.Next()) ++captures;
  }
  state.SetItemsProcessed(captures);
  state.SetLabel(options.read_color ? "colour MJPEG 1280x720 + depth" : "depth only");
}
BENCHMARK(BM_AzureStream)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond);

// Per frame: colour undistorted and depth registered into it.
void BM_AzureRegisterFrame(benchmark::State& state) {
  AzureKinectReader reader(Recording());
  const std::optional<AzureCapture> capture = reader.Next();
  const AzureRegistration registration(reader.calibration());
  for (auto _ : state) {
    benchmark::DoNotOptimize(registration.Apply(*capture->color, *capture->depth));
  }
}
BENCHMARK(BM_AzureRegisterFrame)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
