// `simtree eval tracking`: the paper's Table III columns and more for a `track` output folder.
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/eval/tracking_metrics.h"
#include "simtree/io/ground_truth.h"
#include "simtree/io/trajectories.h"
#include "simtree/tracking/boxes_file.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace simtree::cli {
namespace {

struct EvalTrackingArgs {
  std::string tracks, truth, json;
  double swap_mm = eval::TrackingScoreOptions{}.swap_distance_mm;
};

fs::path Need(const fs::path& path, const std::string& what) {
  if (!fs::exists(path)) throw InputError(path.string(), "", "expected " + what);
  return path;
}

nlohmann::ordered_json ScoresJson(const eval::TrackingScores& s) {
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nullptr; };
  nlohmann::ordered_json out = {{"frames", s.frames},
                                {"visible_samples", s.visible_samples},
                                {"tracked_visible", s.tracked_visible},
                                {"tracked_fraction", s.tracked_fraction},
                                {"tracked_invisible", s.tracked_invisible},
                                {"success_rate", s.success_rate},
                                {"precision", s.precision},
                                {"recall", s.recall},
                                {"f_score", s.f_score},
                                {"f_threshold", s.f_threshold},
                                {"mean_iou", number(s.mean_iou)},
                                {"median_center_error_px", number(s.median_center_error_px)},
                                {"mean_center_error_px", number(s.mean_center_error_px)},
                                {"error_samples", s.error_samples},
                                {"median_error_mm", number(s.median_error_mm)},
                                {"mean_error_mm", number(s.mean_error_mm)},
                                {"p95_error_mm", number(s.p95_error_mm)},
                                {"swap_samples", s.swap_samples},
                                {"swap_events", s.swap_events},
                                {"success_curve", s.success_curve}};
  nlohmann::ordered_json markers = nlohmann::ordered_json::array();
  for (const eval::MarkerTrackingScore& m : s.markers) {
    markers.push_back({{"id", m.marker},
                       {"visible", m.visible},
                       {"tracked_visible", m.tracked_visible},
                       {"median_error_mm", number(m.median_error_mm)},
                       {"swap_samples", m.swap_samples}});
  }
  out["markers"] = markers;
  return out;
}

void PrintScores(const eval::TrackingScores& s) {
  fmt::print("{:<28} {}\n", "frames", s.frames);
  fmt::print("{:<28} {:.4f} ({} of {} visible samples)\n", "tracked fraction", s.tracked_fraction,
             s.tracked_visible, s.visible_samples);
  fmt::print("{:<28} {:.3f}\n", "success rate (AUC)", s.success_rate);
  fmt::print("{:<28} {:.3f} / {:.3f} / {:.3f} (confidence >= {:.2f})\n", "precision / recall / F",
             s.precision, s.recall, s.f_score, s.f_threshold);
  fmt::print("{:<28} {:.3f}\n", "mean IoU", s.mean_iou);
  fmt::print("{:<28} median {:.2f}, mean {:.2f}\n", "centre error (px)", s.median_center_error_px,
             s.mean_center_error_px);
  fmt::print("{:<28} median {:.2f}, mean {:.2f}, p95 {:.2f} ({} samples)\n", "3D error (mm)",
             s.median_error_mm, s.mean_error_mm, s.p95_error_mm, s.error_samples);
  fmt::print("{:<28} {} events ({} samples)\n", "identity swaps", s.swap_events, s.swap_samples);
  fmt::print("{:<28} {}\n", "tracked while hidden", s.tracked_invisible);
  fmt::print("\n{:>6} {:>8} {:>8} {:>9} {:>6}\n", "marker", "visible", "tracked", "median mm",
             "swaps");
  for (const eval::MarkerTrackingScore& m : s.markers) {
    fmt::print("{:>6} {:>8} {:>8} {:>9.2f} {:>6}\n", m.marker, m.visible, m.tracked_visible,
               m.median_error_mm, m.swap_samples);
  }
}

void RunEvalTracking(const EvalTrackingArgs& a) {
  const fs::path tracks = a.tracks;
  fs::path gt = a.truth;
  if (fs::is_directory(gt / "gt")) gt /= "gt";
  const fs::path boxes_path = Need(tracks / "boxes.csv", "boxes.csv (what `track` writes)");
  const fs::path traj_path = Need(tracks / "trajectories.csv", "trajectories.csv");
  const fs::path gt_boxes = Need(gt / "markers_2d.json", "markers_2d.json (a synth capture's gt/)");
  const fs::path gt_traj =
      Need(gt / "trajectories.csv", "trajectories.csv (a synth capture's gt/)");
  eval::TrackingScoreOptions options;
  options.swap_distance_mm = a.swap_mm;
  const eval::TrackingScores scores =
      eval::ScoreTracking(tracking::ReadBoxesCsv(boxes_path), ReadTrajectoriesCsv(traj_path),
                          ReadMarkers2d(gt_boxes), ReadTrajectoriesCsv(gt_traj), options);
  PrintScores(scores);
  if (!a.json.empty()) {
    RefuseToOverwriteInputs(a.json, {boxes_path, traj_path, gt_boxes, gt_traj});
    WriteFileAtomically(a.json, ScoresJson(scores).dump(1) + "\n");
  }
}

}  // namespace

void RegisterEvalTracking(CLI::App& eval) {
  auto args = std::make_shared<EvalTrackingArgs>();
  CLI::App* sub = eval.add_subcommand(
      "tracking",
      "Marker tracking (a `track` folder) against a synth capture's truth: the paper's Table III "
      "columns (success rate, precision, recall, F-score; docs/tracking.md), centre error (px), "
      "3D error (mm), identity swaps and the share of visible samples tracked");
  sub->add_option("tracks", args->tracks,
                  "The folder `simtree track` wrote (boxes.csv, "
                  "trajectories.csv)")
      ->required()
      ->check(CLI::ExistingDirectory);
  sub->add_option("--gt", args->truth, "The synth capture (or its gt/ folder)")
      ->required()
      ->check(CLI::ExistingDirectory);
  sub->add_option("--swap-mm", args->swap_mm,
                  "A tracked centre this close to another marker's true centre (and farther "
                  "from its own) is an identity swap (mm)")
      ->capture_default_str();
  sub->add_option("--json", args->json, "Also write the scores as JSON");
  sub->footer("\nExample:\n  simtree eval tracking tracks/ --gt capture/ --json scores.json\n");
  sub->callback([args] { RunEvalTracking(*args); });
}

}  // namespace simtree::cli
