#include "simtree/eval/identification_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "simtree/core/statistics.h"
#include "simtree/core/units.h"

namespace simtree::eval {
namespace {

ValueScore Score(double truth_f, double truth_z, double f, double z) {
  ValueScore s;
  s.truth_frequency_hz = truth_f;
  s.truth_damping = truth_z;
  s.frequency_hz = f;
  s.damping_ratio = z;
  s.frequency_error = std::isfinite(f) ? std::abs(f / truth_f - 1.0) : kNaN;
  s.damping_error = std::isfinite(z) ? std::abs(z / truth_z - 1.0) : kNaN;
  return s;
}

void Summarize(const std::vector<const ValueScore*>& values, ScoreSummary& summary) {
  std::vector<double> f, z;
  for (const ValueScore* v : values) {
    if (std::isfinite(v->frequency_error)) {
      f.push_back(v->frequency_error);
      z.push_back(std::isfinite(v->damping_error) ? v->damping_error : kNaN);
      ++summary.scored;
    } else {
      ++summary.not_estimated;
    }
  }
  z.erase(std::remove_if(z.begin(), z.end(), [](double x) { return std::isnan(x); }), z.end());
  summary.median_frequency_error = Median(f);
  summary.median_damping_error = Median(z);
  summary.max_frequency_error = f.empty() ? kNaN : *std::max_element(f.begin(), f.end());
  summary.max_damping_error = z.empty() ? kNaN : *std::max_element(z.begin(), z.end());
}

}  // namespace

LinkScores ScoreLinks(const identification::MaterialsFile& materials, const ModalTruth& truth,
                      std::optional<identification::EstimatorKind> estimator) {
  LinkScores out;
  out.estimator = ToString(estimator.value_or(materials.estimator));
  for (const identification::LinkMaterial& link : materials.links) {
    const ModalTruth::Link* t = nullptr;
    for (const ModalTruth::Link& candidate : truth.links) {
      if (candidate.child == link.child && candidate.parent == link.parent) t = &candidate;
    }
    if (!t) {
      ++out.summary.no_truth;
      continue;
    }
    const identification::ModalEstimate* e = &link.value;
    if (estimator) {
      e = nullptr;
      for (const auto& [kind, value] : link.estimators) {
        if (kind == *estimator) e = &value;
      }
    }
    LinkScore s;
    s.parent = link.parent;
    s.child = link.child;
    s.label = link.label;
    // A link without an estimator's entry: its own status says why (a missing marker), if any.
    const bool why = link.value.status != identification::EstimateStatus::kOk;
    s.status = e ? e->status : (why ? link.value.status : identification::EstimateStatus::kFailed);
    s.message =
        e ? e->message : (why ? link.value.message : "the materials file holds no such estimator");
    const bool ok = e && e->status == identification::EstimateStatus::kOk;
    s.value = Score(t->frequency_hz, t->damping_ratio, ok ? e->frequency_hz : kNaN,
                    ok ? e->damping_ratio : kNaN);
    if (t->peaks.size() > 1 && t->peaks[0].strength > 0) {
      s.runner_up_ratio = t->peaks[1].strength / t->peaks[0].strength;
      s.runner_up_frequency_hz = t->peaks[1].frequency_hz;
    }
    s.nearest_mode_frequency_error = s.value.frequency_error;
    for (const ModalTruth::ModePeak& p : t->peaks) {
      if (ok && p.frequency_hz > 0) {
        s.nearest_mode_frequency_error = std::min(s.nearest_mode_frequency_error,
                                                  std::abs(e->frequency_hz / p.frequency_hz - 1.0));
      }
    }
    out.links.push_back(s);
  }
  std::vector<const ValueScore*> values;
  for (const LinkScore& s : out.links) values.push_back(&s.value);
  const int no_truth = out.summary.no_truth;
  Summarize(values, out.summary);
  out.summary.no_truth = no_truth;
  return out;
}

BranchScores ScoreBranches(const Tree& tree, const ModalTruth& truth) {
  BranchScores out;
  for (const ModalTruth::BranchTruth& t : truth.branches) {
    if (t.branch < 0 || t.branch >= tree.size() || !tree.branches[t.branch].material) continue;
    const Material& m = *tree.branches[t.branch].material;
    BranchScore s;
    s.branch = t.branch;
    s.source = m.source;
    const Mode& dominant = m.mode(ModeKind::kTwistV);
    s.value = Score(t.frequency_hz, t.damping_ratio, dominant.frequency_hz, dominant.damping_ratio);
    out.branches.push_back(s);
  }
  std::vector<const ValueScore*> measured, interpolated;
  for (const BranchScore& s : out.branches) {
    (s.source == MaterialSource::kMeasured ? measured : interpolated).push_back(&s.value);
  }
  Summarize(measured, out.measured);
  Summarize(interpolated, out.interpolated);
  return out;
}

std::string BranchMismatch(const Tree& tree, const Tree& truth_tree, double tolerance_m) {
  if (tree.size() != truth_tree.size()) {
    return fmt::format("{} branches where the truth's tree has {}", tree.size(), truth_tree.size());
  }
  for (int i = 0; i < tree.size(); ++i) {
    const Branch& a = tree.branches[i];
    const Branch& b = truth_tree.branches[i];
    if (a.nodes.empty() || b.nodes.empty()) continue;
    const double apart = std::max((a.nodes.front().position - b.nodes.front().position).norm(),
                                  (a.nodes.back().position - b.nodes.back().position).norm());
    if (apart > tolerance_m) {
      return fmt::format("branch {} lies {:.3f} m from the truth's branch {}", i, apart, i);
    }
  }
  return "";
}

std::string FormatSummary(const std::string& name, const ScoreSummary& s) {
  return fmt::format(
      "{:<24} {:>3} scored  median |df/f| {:>6.2f}%  |dzeta/zeta| {:>6.1f}%  (max {:.2f}% / "
      "{:.1f}%)"
      "{}",
      name, s.scored, 100 * s.median_frequency_error, 100 * s.median_damping_error,
      100 * s.max_frequency_error, 100 * s.max_damping_error,
      s.not_estimated ? fmt::format(", {} not estimated", s.not_estimated) : "");
}

std::string FormatLinkScores(const LinkScores& scores) {
  std::string out = fmt::format(
      "| link | status | f true | f | err | zeta true | zeta | err |\n"
      "| --- | --- | --- | --- | --- | --- | --- | --- |\n");
  for (const LinkScore& s : scores.links) {
    out += fmt::format("| {} | {} | {:.4f} | {:.4f} | {:.2f}% | {:.4f} | {:.4f} | {:.1f}% |\n",
                       s.label, ToString(s.status), s.value.truth_frequency_hz,
                       s.value.frequency_hz, 100 * s.value.frequency_error, s.value.truth_damping,
                       s.value.damping_ratio, 100 * s.value.damping_error);
  }
  return out;
}

}  // namespace simtree::eval
