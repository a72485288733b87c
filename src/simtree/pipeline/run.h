#pragma once
// `simtree run`: a capture folder to a simulation-ready tree in one call, one folder per stage
// under the result folder, a manifest (run.json) of what ran, and resumption of what did not
// change.
//
//   scans -> preprocess -> register (+ the pull camera) -> reconstruct --------------------+
//   pull stream -> track -> identify (markers placed on the reconstructed tree) -> build <-+
//   build -> simulate (the capture's pull, replayed) -> render (beside the capture) -> report
//
// Every stage writes its folder whole or not at all; a stage whose inputs, options and outputs
// match run.json is reused, and once one stage runs every later one runs too. A failing stage
// leaves the earlier ones in place and its error names it. The capture's gt/ is never read.
//
// Usage:
//   simtree::pipeline::RunOptions options;
//   options.tracks = "tracks.csv";  // until tracking is a stage
//   const simtree::pipeline::RunResult result =
//       simtree::pipeline::Run("capture/", "result/", options);
//   // result.stages: what each stage did; result/report.html: the page to open

#include <filesystem>
#include <string>
#include <vector>

#include "simtree/pipeline/manifest.h"

namespace simtree::pipeline {

// The stages in order ("preprocess", "register", ..., "report").
const std::vector<std::string>& StageNames();

struct RunOptions {
  // Marker trajectories (simtree.trajectories, pull camera frame) copied into track/ instead of
  // tracking the pull stream; empty: track.
  std::filesystem::path tracks;
  std::string from;    // redo this stage and every later one (empty: only what changed)
  std::string until;   // stop after this stage (empty: the last)
  bool force = false;  // redo every stage
  // Leaf markers (no marker links to them) kept from identification, so that the simulated
  // chain can be scored on markers identification never saw (>= 0).
  int held_out_markers = 2;
  bool render = true;      // draw the simulation beside the capture's frames (needs OpenGL)
  int render_width = 640;  // pixels of the simulated half of a side-by-side frame (> 0)
  // The report's JavaScript libraries may be missing (the page then says so) instead of failing.
  bool allow_missing_javascript = true;
  uint64_t seed = 1;  // of every random choice of the stages

  // Throws InputError naming the field ("from": not a stage name, ...).
  void Validate() const;
  // The options as written into run.json.
  nlohmann::ordered_json ToJson() const;
};

struct RunResult {
  std::filesystem::path result_dir;
  std::vector<StageRecord> stages;  // every stage, in order, as run.json has them
  double wall_s = 0.0;
  int ran = 0, reused = 0;
  std::filesystem::path report;  // result/report.html when the report stage ran or was reused
};

// The checks made before any work: the capture has scans/ with views, pull/ with frames and
// markers.json; the result folder is not the capture nor inside it; the trajectories given exist
// (or tracking is built). Throws InputError naming the folder or file.
void CheckInputs(const std::filesystem::path& capture, const std::filesystem::path& result,
                 const RunOptions& options);

// Runs the pipeline (see above). Throws InputError before any work for bad options or inputs;
// a failing stage is recorded in run.json and rethrown as StageError naming it.
RunResult Run(const std::filesystem::path& capture, const std::filesystem::path& result,
              const RunOptions& options = {});

}  // namespace simtree::pipeline
