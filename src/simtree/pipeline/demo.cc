#include "simtree/pipeline/demo.h"

#include <chrono>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/io/ground_truth.h"
#include "simtree/io/trajectories.h"
#include "simtree/pipeline/detail/tracking_stage.h"
#include "simtree/report/report.h"
#include "simtree/synth/synth.h"
#include "simtree/tracking/tracker_error.h"

namespace fs = std::filesystem;

namespace simtree::pipeline {
namespace {

bool Synthesise(const fs::path& capture, const DemoOptions& options) {
  if (fs::exists(capture / "capture.json") && fs::exists(capture / "gt" / "trajectories.csv")) {
    spdlog::info("demo: reusing the capture in {}", capture.string());
    return false;
  }
  synth::SynthOptions synth;
  synth.species = options.species;
  synth.seed = options.seed;
  synth.quick = true;
  synth.views = options.views;
  synth.duration_s = options.duration_s;
  spdlog::info("demo: synthesising {} seed {} into {}", synth.species, synth.seed,
               capture.string());
  const synth::SynthReport report = synth::RunSynth(synth, capture);
  spdlog::info("demo: {}", report.Summary());
  return true;
}

// The capture's true marker centres with a tracker's errors (a stand-in for tracking).
fs::path StandInTracks(const fs::path& capture, const fs::path& out) {
  const fs::path path = out / "tracks.csv";
  const Trajectories truth = ReadTrajectoriesCsv(capture / "gt" / "trajectories.csv");
  const std::vector<MarkerFrame2d> visibility = ReadMarkers2d(capture / "gt" / "markers_2d.json");
  WriteTrajectoriesCsv(tracking::SimulateTrackerError(truth, {}, &visibility), path);
  return path;
}

}  // namespace

void DemoOptions::Validate() const {
  if (!(duration_s >= 6.9) || duration_s > 60) {
    throw InputError("demo options", "duration_s",
                     fmt::format("expected 6.9 to 60 s (5 s of free decay after the release at "
                                 "1.8 s), got {}",
                                 duration_s));
  }
  if (views < 2 || views > 36) {
    throw InputError("demo options", "views", fmt::format("expected 2 to 36, got {}", views));
  }
  run.Validate();
}

DemoResult RunDemo(const fs::path& out, const DemoOptions& options) {
  options.Validate();
  const auto start = std::chrono::steady_clock::now();
  DemoResult demo;
  demo.capture = out / "capture";
  demo.result = out / "result";
  fs::create_directories(out);
  demo.synthesised = Synthesise(demo.capture, options);
  RunOptions run = options.run;
  run.render = options.render;
  if (!detail::TrackingBuilt() || !fs::exists(demo.capture / "pull" / "init.json")) {
    spdlog::warn(
        "demo: {}: the trajectories are the capture's true marker centres with a tracker's "
        "errors added ({}/tracks.csv)",
        detail::TrackingBuilt() ? "the capture has no pull/init.json to start tracking from"
                                : "tracking is not a stage of this build",
        out.string());
    run.tracks = StandInTracks(demo.capture, out);
    demo.simulated_tracks = true;
  }
  demo.run = Run(demo.capture, demo.result, run);
  demo.evaluation = eval::EvaluateRun(demo.result, demo.capture);
  eval::WriteRunEvaluation(demo.evaluation, demo.result / "eval");
  report::ReportOptions report;
  report.allow_missing_javascript = run.allow_missing_javascript;
  demo.report = report::WriteReport(demo.result, report).path;
  demo.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return demo;
}

}  // namespace simtree::pipeline
