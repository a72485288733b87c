#pragma once
// Scores of an identification against synth's FEM truth (gt/modal.json): per marker link the
// relative error of the natural frequency and damping ratio (paper Table IV's quantities), for the
// chosen estimator and for every other estimator that was run; per branch, the error of the
// values a simulation-ready tree carries (measured or interpolated).

#include <optional>
#include <string>
#include <vector>

#include "simtree/core/tree.h"
#include "simtree/identification/materials_file.h"
#include "simtree/io/ground_truth.h"

namespace simtree::eval {

struct ValueScore {
  double truth_frequency_hz = 0.0, truth_damping = 0.0;
  double frequency_hz = 0.0, damping_ratio = 0.0;     // NaN when not estimated
  double frequency_error = 0.0, damping_error = 0.0;  // relative, |estimate / truth - 1|; NaN
};

struct LinkScore {
  int parent = -1, child = 0;
  std::string label;
  identification::EstimateStatus status = identification::EstimateStatus::kOk;
  std::string message;  // the estimator's note, or why there is no value
  ValueScore value;
  // How clear the truth's dominant mode is: the runner-up's spectral peak over the dominant's
  // (0 when the truth lists one mode). Near 1, noise or a neighbouring mode can swap the two.
  double runner_up_ratio = 0.0;
  double runner_up_frequency_hz = 0.0;
  // |estimate / f - 1| for the nearest of the truth's strongest modes (its `peaks`): small when
  // the estimate found a real mode of the link, not necessarily the dominant one. NaN without an
  // estimate.
  double nearest_mode_frequency_error = 0.0;
};

struct ScoreSummary {
  int scored = 0;         // with a truth and an estimate
  int not_estimated = 0;  // with a truth, no estimate (status says why)
  int no_truth = 0;       // estimated but the truth has no such link or branch
  double median_frequency_error = 0.0, median_damping_error = 0.0;  // NaN when none scored
  double max_frequency_error = 0.0, max_damping_error = 0.0;
};

struct LinkScores {
  std::string estimator;
  std::vector<LinkScore> links;
  ScoreSummary summary;
};

// Links of `materials` against the truth's links (matched by parent and child marker ids), read
// from `estimator`'s column (default: the file's chosen estimator).
LinkScores ScoreLinks(const identification::MaterialsFile& materials, const ModalTruth& truth,
                      std::optional<identification::EstimatorKind> estimator = std::nullopt);

struct BranchScore {
  int branch = 0;
  MaterialSource source = MaterialSource::kDefault;
  ValueScore value;  // the branch's dominant value: its twist mode (which carries it)
};

struct BranchScores {
  std::vector<BranchScore> branches;
  ScoreSummary measured, interpolated;
};

// Every branch of a simulation-ready tree against the truth's per-branch values.
BranchScores ScoreBranches(const Tree& simulation_ready, const ModalTruth& truth);

// Why `tree`'s branches are not `truth_tree`'s, branch for branch (another count, or a branch
// starting or ending more than `tolerance_m` away: a reconstructed or renumbered tree, whose
// branch ids the truth's per-branch values do not describe); empty when they are.
std::string BranchMismatch(const Tree& tree, const Tree& truth_tree, double tolerance_m = 0.01);

// Markdown-ish tables for reports.
std::string FormatLinkScores(const LinkScores& scores);
std::string FormatSummary(const std::string& name, const ScoreSummary& summary);

}  // namespace simtree::eval
