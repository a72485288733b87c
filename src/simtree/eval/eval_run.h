#pragma once
// A whole `simtree run` result folder against a synth capture's truth (gt/), every stage in one
// JSON document and one Markdown table (`simtree eval RESULT --gt CAPTURE`):
//
//  - registration: every registered view's and the pull camera's pose error, measured at the true
//    tree (ViewPoseError, relative to the anchor view);
//  - reconstruction: the static tree taken into the truth's frame by the anchor view's poses,
//    scored by ScoreAgainstTruth (recall, precision, skeleton distance, radius error);
//  - tracking: track/boxes.csv and trajectories.csv against gt/markers_2d.json and
//    gt/trajectories.csv (ScoreTracking, paper Table III), when the run tracked (not --tracks);
//  - identification: every marker link against the FEM truth (ScoreLinks);
//  - the chain: the simulated held-out markers (identify/placements.json "held_out": markers
//    identification never saw) against their true motion over the first `chain_window_s` after
//    the true release, both as displacements from the first frame in the pull camera's frame:
//    normalised RMSE (RMS of the difference over RMS of the truth), dominant frequency and decay.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace simtree::eval {

struct RunEvalOptions {
  double chain_window_s = 5.0;  // s after the release the chain is scored over (> 0)
  double min_frequency_hz = 0.2, max_frequency_hz = 10.0;  // band of the dominant frequency

  // Throws InputError ("run eval options", the field) for a value out of range.
  void Validate() const;
};

// One held-out marker: simulation against truth.
struct ChainMarkerScore {
  int marker = 0;
  std::string label;
  int samples = 0;
  double nrmse = 0.0;
  double true_rms_m = 0.0;
  double simulated_frequency_hz = 0.0, true_frequency_hz = 0.0;
  double simulated_decay = 0.0, true_decay = 0.0;  // damping ratio from the envelope's decay
};

struct RunEvaluation {
  nlohmann::ordered_json json;  // simtree.eval_run v1
  std::string markdown;
  std::vector<ChainMarkerScore> chain;
  double chain_median_nrmse = 0.0;  // NaN without held-out markers
};

// Throws InputError when the capture has no gt/ or the result folder lacks what a scored part
// needs; a part whose files are missing is reported as not scored.
RunEvaluation EvaluateRun(const std::filesystem::path& result_dir,
                          const std::filesystem::path& capture_dir,
                          const RunEvalOptions& options = {});

// <out_dir>/eval.json and eval.md (each written atomically).
void WriteRunEvaluation(const RunEvaluation& evaluation, const std::filesystem::path& out_dir);

}  // namespace simtree::eval
