// Time per pair of views, declined pairs apart: every pair of synthetic captures' views registered
// alone (RegisterPair, one after the other, so each pair's time is its own), with what each
// attempt found and took, scored against the truth (gt/scan_poses.json). The evidence behind
// PairOptions::decline_below_overlap (which first overlaps a retry has rescued) and the figures
// of docs/benchmarks.md ("Declining hopeless pairs").
//
//   registration_failfast --views 6 --species acer_palmatum magnolia acer_rubrum --seeds 2
//   registration_failfast --views 6 --span 3 --multiview            # as `register --span 3` runs
//   registration_failfast --views 6 --span 3 --multiview --decline 0 --budget 0 --chain 0  # before
//   registration_failfast --captures scene1/ --span 3 --markdown t.md

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <open3d/utility/Logging.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "simtree/core/tree_json.h"
#include "simtree/eval/registration_metrics.h"
#include "simtree/io/capture.h"
#include "simtree/io/ground_truth.h"
#include "simtree/preprocessing/preprocess.h"
#include "simtree/registration/register.h"
#include "synth_capture_set.h"

namespace fs = std::filesystem;
using namespace simtree;

namespace {

struct BenchArgs : bench::CaptureSetArgs {
  BenchArgs() { views = 6; }
  int span = 0;                   // 0: every pair
  std::optional<double> decline;  // PairOptions::decline_below_overlap (default: the library's)
  std::optional<double> budget;   // PairOptions::max_pair_seconds
  std::optional<double> chain;    // MultiViewOptions::chained_decline_factor
  std::vector<std::string> only;  // "source:target" pairs to run (empty: all)
  bool near_half = false;         // each view keeps the half of the tree facing its camera
  bool multiview = false;         // the pairs as RegisterViews runs them (all at once)
};

struct PairRow {
  std::string capture, source, target;
  double angle_deg = 0.0;  // true gap around the tree
  registration::PairResult result;
  eval::PoseError error;
  bool right = false;            // within 2 deg and 2 cm at the tree
  eval::PoseError first_error;   // of the first attempt's result
  double capture_seconds = 0.0;  // --multiview: RegisterViews' time, on the capture's first row
};

// Keeps the points on the camera's side of the vertical plane through the trunk (synth stands
// the tree's base at the world origin, Z up): a view that sees only the near half of the tree,
// as through foliage, so that opposite views share (next to) nothing.
void KeepNearHalf(const Eigen::Isometry3d& world_from_camera, open3d::geometry::PointCloud& cloud) {
  Eigen::Vector3d toward = world_from_camera.translation();
  toward.z() = 0.0;
  toward.normalize();
  std::vector<size_t> keep;
  for (size_t i = 0; i < cloud.points_.size(); ++i) {
    Eigen::Vector3d p = world_from_camera * cloud.points_[i];
    p.z() = 0.0;
    if (p.dot(toward) > 0.0) keep.push_back(i);
  }
  cloud = *cloud.SelectByIndex(keep);
}

std::vector<PairRow> RunCapture(const BenchArgs& args, const fs::path& root,
                                const std::string& label) {
  fmt::print(stderr, "{}\n", label);
  const preprocessing::PreprocessOptions preprocess;
  const registration::RegistrationViewOptions view_options;
  registration::MultiViewOptions options;
  if (args.decline) options.pair.decline_below_overlap = *args.decline;
  if (args.budget) options.pair.max_pair_seconds = *args.budget;
  if (args.chain) options.chained_decline_factor = *args.chain;
  options.neighbour_span = args.span > 0 ? args.span : 1000;
  options.Validate();
  const Capture capture = OpenCapture(root);
  const std::vector<ViewPose> truth = ReadScanPoses(root / "gt" / "scan_poses.json");
  std::vector<preprocessing::PreprocessedView> clean =
      preprocessing::PreprocessCaptureViews(capture, preprocess);
  if (args.near_half) {
    for (size_t v = 0; v < clean.size() && v < truth.size(); ++v) {
      if (clean[v].result) KeepNearHalf(truth[v].world_from_camera, clean[v].result->cloud);
    }
  }
  const std::vector<registration::RegistrationView> views =
      registration::PrepareViews(clean, view_options);
  const std::vector<Eigen::Vector3d> tree =
      eval::TreeSamplePoints(ReadTreeJson(root / "gt" / "tree.json"));
  auto true_pose = [&](const std::string& name) {
    const auto it =
        std::find_if(truth.begin(), truth.end(), [&](const ViewPose& p) { return p.name == name; });
    if (it == truth.end()) throw std::runtime_error("no true pose for " + name);
    return it->world_from_camera;
  };
  std::vector<PairRow> rows;
  std::vector<registration::PairEdge> edges;
  double capture_seconds = 0.0;
  if (args.multiview) {
    const registration::MultiViewResult result = registration::RegisterViews(views, options);
    edges = result.pairs;
    capture_seconds = result.seconds;
  }
  size_t next_edge = 0;
  for (const auto& [s, t] : registration::ViewPairs(static_cast<int>(views.size()), options)) {
    const size_t e = next_edge++;
    const std::string key = views[s].name + ":" + views[t].name;
    if (!args.only.empty() &&
        std::find(args.only.begin(), args.only.end(), key) == args.only.end()) {
      continue;
    }
    PairRow row;
    row.capture = label;
    row.source = views[s].name;
    row.target = views[t].name;
    row.result = args.multiview ? edges[e].result
                                : registration::RegisterPair(views[s], views[t], options.pair);
    if (rows.empty()) row.capture_seconds = capture_seconds;
    const Eigen::Isometry3d world_from_source = true_pose(row.source);
    const Eigen::Isometry3d world_from_target = true_pose(row.target);
    row.angle_deg = eval::ViewAngleDeg(world_from_source, world_from_target);
    row.error = eval::PairPoseError(row.result.target_from_source, world_from_source,
                                    world_from_target, tree);
    row.right = row.error.Within();
    if (!row.result.attempts.empty()) {
      row.first_error = eval::PairPoseError(row.result.attempts.front().target_from_source,
                                            world_from_source, world_from_target, tree);
    }
    fmt::print(stderr, "  {} -> {}: {:.0f} deg apart, {} {}, {:.2f} s\n", row.source, row.target,
               row.angle_deg, row.result.ok() ? "ok" : "failed", row.right ? "right" : "wrong",
               row.result.seconds);
    rows.push_back(std::move(row));
  }
  return rows;
}

std::string Markdown(const std::vector<PairRow>& rows) {
  std::string md =
      "| capture | pair | apart (deg) | outcome | error (deg / mm) | first overlap | kept "
      "(attempt, overlap) | attempts run | time (s) |\n"
      "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  std::vector<double> declined_s, trusted_s, rescued_first;
  int declined = 0, trusted = 0, trusted_wrong = 0, rescued = 0;
  for (const PairRow& r : rows) {
    const registration::PairResult& p = r.result;
    const double first = p.attempts.empty() ? NAN : p.attempts.front().view_overlap;
    md += fmt::format(
        "| {} | {}->{} | {:.0f} | {}{} | {:.2f} / {:.0f} | {:.2f} | {}, {:.2f} | {} | "
        "{:.2f} |\n",
        r.capture, r.source, r.target, r.angle_deg, p.ok() ? "ok" : "declined",
        p.declined.empty() ? "" : " early", r.error.rotation_deg, 1e3 * r.error.tree_rms_m, first,
        ToString(p.attempt), p.view_overlap, p.attempts.size(), p.seconds);
    if (p.ok()) {
      ++trusted;
      trusted_s.push_back(p.seconds);
      if (!r.right) ++trusted_wrong;
      if (p.attempt != registration::PairAttempt::kFirst) {
        ++rescued;
        rescued_first.push_back(first);
      }
    } else {
      ++declined;
      declined_s.push_back(p.seconds);
    }
  }
  std::sort(rescued_first.begin(), rescued_first.end());
  md += fmt::format(
      "\n{} pairs: {} trusted ({} wrong), median {:.2f} s, largest {:.2f} s; {} declined, median "
      "{:.2f} s, largest {:.2f} s. {} trusted pairs were found by a retry, their first attempts "
      "overlapping {}.\n",
      rows.size(), trusted, trusted_wrong, bench::Median(trusted_s), bench::Largest(trusted_s),
      declined, bench::Median(declined_s), bench::Largest(declined_s), rescued,
      rescued_first.empty() ? "-" : fmt::format("{:.2f}", fmt::join(rescued_first, ", ")));
  return md;
}

nlohmann::ordered_json Json(const std::vector<PairRow>& rows) {
  nlohmann::ordered_json doc = nlohmann::ordered_json::array();
  for (const PairRow& r : rows) {
    const registration::PairResult& p = r.result;
    auto checks = [](const std::vector<registration::PairCheck>& failed) {
      nlohmann::ordered_json names = nlohmann::ordered_json::array();
      for (registration::PairCheck c : failed) names.push_back(ToString(c));
      return names;
    };
    nlohmann::ordered_json attempts = nlohmann::ordered_json::array();
    for (const auto& run : p.attempts) {
      attempts.push_back({{"attempt", ToString(run.attempt)},
                          {"view_overlap", run.view_overlap},
                          {"seconds", run.seconds},
                          {"refined", run.refined},
                          {"coarse_overlap", run.coarse_overlap},
                          {"failed_checks", checks(run.failed_checks)}});
    }
    nlohmann::ordered_json pose = nlohmann::ordered_json::array();
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) pose.push_back(p.target_from_source.matrix()(i, j));
    }
    doc.push_back({{"capture", r.capture},
                   {"source", r.source},
                   {"target", r.target},
                   {"angle_deg", r.angle_deg},
                   {"ok", p.ok()},
                   {"right", r.right},
                   {"rotation_error_deg", r.error.rotation_deg},
                   {"tree_rms_mm", 1e3 * r.error.tree_rms_m},
                   {"first_rotation_error_deg", r.first_error.rotation_deg},
                   {"first_tree_rms_mm", 1e3 * r.first_error.tree_rms_m},
                   {"capture_seconds", r.capture_seconds},
                   {"status", p.status},
                   {"declined", p.declined},
                   {"attempt", ToString(p.attempt)},
                   {"view_overlap", p.view_overlap},
                   {"seconds", p.seconds},
                   {"attempts", attempts},
                   {"target_from_source", pose}});
  }
  return doc;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Time per pair of views (declined pairs apart), against synth captures' truth"};
  BenchArgs args;
  args.AddOptions(app);
  app.add_option("--views", args.views, "Scan views per synthetic capture")->capture_default_str();
  app.add_option("--span", args.span, "Pair each view with this many next ones (0: every pair)")
      ->capture_default_str();
  app.add_option("--decline", args.decline, "PairOptions::decline_below_overlap (0: never)");
  app.add_option("--budget", args.budget, "PairOptions::max_pair_seconds (0: no limit)");
  app.add_flag("--near-half", args.near_half,
               "Each view keeps the half of the tree facing its camera (opposite views share "
               "next to nothing)");
  app.add_flag("--multiview", args.multiview,
               "The pairs as RegisterViews runs them, all at once (times under each other's load)");
  app.add_option("--pairs", args.only, "Only these pairs, as source:target view names");
  app.add_option("--chain", args.chain, "MultiViewOptions::chained_decline_factor (0: never)");
  CLI11_PARSE(app, argc, argv);
  open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);

  std::vector<PairRow> rows;
  for (const bench::CaptureEntry& capture : bench::ResolveCaptures(args)) {
    for (PairRow& r : RunCapture(args, capture.root, capture.label)) rows.push_back(std::move(r));
  }
  bench::WriteOutputs(args, Markdown(rows), Json(rows));
  return 0;
}
