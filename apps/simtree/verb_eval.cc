#include <cmath>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/tree_json.h"
#include "simtree/eval/identification_metrics.h"
#include "simtree/identification/materials_file.h"
#include "simtree/io/ground_truth.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace simtree::cli {
namespace {

// `gt` may be the capture, its gt/ folder or the file itself.
fs::path TruthFile(const std::string& given, const char* name) {
  fs::path path = given;
  if (fs::is_directory(path) && fs::exists(path / "gt" / name)) return path / "gt" / name;
  if (fs::is_directory(path)) path /= name;
  if (!fs::exists(path)) {
    throw InputError(given, "",
                     fmt::format("expected {} (a synth capture, its gt/ folder or "
                                 "the file)",
                                 name));
  }
  return path;
}

// The truth's per-branch values describe the branches of the truth's tree: a tree built on
// gt/tree.json is scored branch by branch; a run's reconstructed tree numbers its branches its own
// way, and scoring it by id would compare unrelated branches.
void CheckTreeIsTheTruths(const Tree& tree, const std::string& tree_path,
                          const fs::path& truth_tree_path) {
  if (!fs::exists(truth_tree_path)) return;
  const std::string why = eval::BranchMismatch(tree, ReadTreeJson(truth_tree_path.string()));
  if (why.empty()) return;
  throw InputError(tree_path, "",
                   fmt::format("not built on the truth's tree {} ({}); a run's tree is scored by "
                               "`simtree eval RESULT --gt CAPTURE`",
                               truth_tree_path.string(), why));
}

nlohmann::ordered_json SummaryJson(const eval::ScoreSummary& s) {
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nullptr; };
  return {{"scored", s.scored},
          {"not_estimated", s.not_estimated},
          {"no_truth", s.no_truth},
          {"median_frequency_error", number(s.median_frequency_error)},
          {"median_damping_error", number(s.median_damping_error)},
          {"max_frequency_error", number(s.max_frequency_error)},
          {"max_damping_error", number(s.max_damping_error)}};
}

nlohmann::ordered_json LinkScoresJson(const eval::LinkScores& scores) {
  auto number = [](double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nullptr; };
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const eval::LinkScore& s : scores.links) {
    out.push_back({{"label", s.label},
                   {"parent", s.parent},
                   {"child", s.child},
                   {"status", ToString(s.status)},
                   {"message", s.message},
                   {"truth_frequency_hz", s.value.truth_frequency_hz},
                   {"truth_damping_ratio", s.value.truth_damping},
                   {"frequency_hz", number(s.value.frequency_hz)},
                   {"damping_ratio", number(s.value.damping_ratio)},
                   {"frequency_error", number(s.value.frequency_error)},
                   {"damping_error", number(s.value.damping_error)},
                   {"runner_up_ratio", s.runner_up_ratio},
                   {"runner_up_frequency_hz", s.runner_up_frequency_hz},
                   {"nearest_mode_frequency_error", number(s.nearest_mode_frequency_error)}});
  }
  return out;
}

void RegisterEvalIdentification(CLI::App& eval) {
  struct Args {
    std::string materials, truth, tree, json;
  };
  auto args = std::make_shared<Args>();
  CLI::App* sub = eval.add_subcommand(
      "identification",
      "Natural frequency and damping of every marker link (materials.json from `identify`) "
      "against the FEM truth of a synth capture (gt/modal.json), per estimator; with --tree, "
      "every branch of a simulation-ready tree (measured and interpolated)");
  sub->add_option("materials", args->materials, "materials.json from `simtree identify`")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--gt", args->truth, "The synth capture, its gt/ folder, or gt/modal.json")
      ->required();
  sub->add_option("--tree", args->tree, "A simulation-ready tree from `simtree build`")
      ->check(CLI::ExistingFile);
  sub->add_option("--json", args->json, "Also write the scores as JSON");
  sub->footer(Examples({
      "simtree eval identification materials.json --gt scene/",
      "simtree eval identification materials.json --gt scene/gt/modal.json --tree simready.json "
      "--json scores.json",
  }));
  sub->callback([args] {
    const fs::path truth_path = TruthFile(args->truth, "modal.json");
    const ModalTruth truth = ReadModalTruth(truth_path);
    const identification::MaterialsFile materials =
        identification::ReadMaterialsJson(args->materials);
    nlohmann::ordered_json out = {{"format", "simtree.eval_identification"},
                                  {"version", 1},
                                  {"materials", args->materials},
                                  {"truth", truth_path.string()}};
    // The chosen estimator first, then every other one the file holds.
    std::vector<std::optional<identification::EstimatorKind>> kinds = {std::nullopt};
    for (identification::EstimatorKind kind : identification::AllEstimators()) {
      if (kind != materials.estimator) kinds.push_back(kind);
    }
    nlohmann::ordered_json per_estimator = nlohmann::ordered_json::object();
    for (const auto& kind : kinds) {
      const eval::LinkScores scores = eval::ScoreLinks(materials, truth, kind);
      if (scores.summary.scored == 0 && kind) continue;  // not in the file
      if (!kind) std::printf("%s\n", eval::FormatLinkScores(scores).c_str());
      std::printf("%s\n", FormatSummary(scores.estimator, scores.summary).c_str());
      per_estimator[scores.estimator] = SummaryJson(scores.summary);
      per_estimator[scores.estimator]["per_link"] = LinkScoresJson(scores);
    }
    out["links"] = per_estimator;
    if (!args->tree.empty()) {
      const Tree tree = ReadTreeJson(args->tree);
      CheckTreeIsTheTruths(tree, args->tree, truth_path.parent_path() / "tree.json");
      const eval::BranchScores branches = eval::ScoreBranches(tree, truth);
      std::printf("%s\n", FormatSummary("branches, measured", branches.measured).c_str());
      std::printf("%s\n", FormatSummary("branches, interpolated", branches.interpolated).c_str());
      out["branches"] = {{"measured", SummaryJson(branches.measured)},
                         {"interpolated", SummaryJson(branches.interpolated)}};
    }
    if (!args->json.empty()) {
      RefuseToOverwriteInputs(args->json, {args->materials, truth_path});
      WriteFileAtomically(args->json, out.dump(1) + "\n");
    }
  });
}

}  // namespace

void RegisterEvalTracking(CLI::App& eval);  // verb_eval_tracking.cc

void RegisterEval(CLI::App& app) {
  CLI::App* eval = app.add_subcommand(
      "eval", "Score a stage's output against the ground truth of a synth capture (gt/)");
  eval->require_subcommand(0, 1);
  RegisterEvalIdentification(*eval);
  RegisterEvalTracking(*eval);
  AddEvalRun(*eval);
}

}  // namespace simtree::cli
