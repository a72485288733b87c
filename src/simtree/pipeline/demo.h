#pragma once
// `simtree demo`: the pipeline shown end to end on a synthetic capture, in a few minutes:
// synth (the default species, small: 4 views, a 7 s pull stream) into OUT/capture, run into
// OUT/result, eval against the capture's truth into OUT/result/eval, and the report rewritten
// with the scores. A capture already in OUT/capture is reused, and so is every stage that has
// not changed.
//
// While tracking is not a stage of this build, the trajectories run uses are the capture's true
// marker centres with a tracker's errors added (tracking/tracker_error.h: 2.5 mm RMS, gaps where
// the tape is hidden, rare jumps), written to OUT/tracks.csv; the demo says so when it starts.

#include <cstdint>
#include <filesystem>
#include <string>

#include "simtree/eval/eval_run.h"
#include "simtree/pipeline/run.h"

namespace simtree::pipeline {

struct DemoOptions {
  std::string species = "acer_rubrum";  // a synth preset
  uint64_t seed = 7;                    // of the synthetic tree and capture
  double duration_s = 7.0;  // pull stream length (s, >= 6.9: 5 s of free decay after the release)
  int views = 4;            // static scan views (>= 2)
  bool render = true;       // side-by-side frames
  RunOptions run;           // tracks and render are set by the demo

  // Throws InputError naming the field.
  void Validate() const;
};

struct DemoResult {
  std::filesystem::path capture, result, report;
  bool synthesised = false;       // false: the capture was there already
  bool simulated_tracks = false;  // the trajectories are the truth with a tracker's errors
  RunResult run;
  eval::RunEvaluation evaluation;
  double wall_s = 0.0;
};

// Throws as RunSynth, Run and EvaluateRun do.
DemoResult RunDemo(const std::filesystem::path& out, const DemoOptions& options = {});

}  // namespace simtree::pipeline
