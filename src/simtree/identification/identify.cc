#include "simtree/identification/identify.h"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/identification/detail/link_model_choice.h"
#include "simtree/identification/detail/shared_pole_uncertainty.h"

namespace simtree::identification {

const SignalEstimate* LinkIdentification::Find(EstimatorKind kind) const {
  for (const SignalEstimate& e : estimates) {
    if (e.estimator == kind) return &e;
  }
  return nullptr;
}

MaterialRanges ComputeRanges(const std::vector<LabeledEstimate>& links,
                             const RangeOptions& bounds) {
  bounds.Validate();
  MaterialRanges r;
  r.links = static_cast<int>(links.size());
  r.bounds = bounds;
  // Within the bound. A value whose estimator gives no uncertainty at all (both NaN: the spectral
  // estimators) counts; one whose uncertainty is missing or infinite while its estimator
  // gives them (a fit whose covariance broke down) does not.
  auto certain = [](double value, double std, double bound) {
    return std::isfinite(std) && std / value <= bound;
  };
  auto widen = [](double value, double* lo, double* hi) {
    *lo = std::isnan(*lo) ? value : std::min(*lo, value);
    *hi = std::isnan(*hi) ? value : std::max(*hi, value);
  };
  for (const LabeledEstimate& link : links) {
    const ModalEstimate& e = link.value;
    if (e.status != EstimateStatus::kOk) continue;
    ++r.measured;
    widen(e.frequency_hz, &r.all_min_frequency_hz, &r.all_max_frequency_hz);
    widen(e.damping_ratio, &r.all_min_damping, &r.all_max_damping);
    const bool no_uncertainty = std::isnan(e.frequency_std_hz) && std::isnan(e.damping_std);
    const bool f_ok = no_uncertainty || certain(e.frequency_hz, e.frequency_std_hz,
                                                bounds.max_frequency_relative_std);
    const bool z_ok =
        no_uncertainty || certain(e.damping_ratio, e.damping_std, bounds.max_damping_relative_std);
    if (f_ok) {
      ++r.frequency_count;
      widen(e.frequency_hz, &r.min_frequency_hz, &r.max_frequency_hz);
    }
    if (z_ok) {
      ++r.damping_count;
      widen(e.damping_ratio, &r.min_damping, &r.max_damping);
    }
    if (!f_ok || !z_ok) r.uncertain.push_back(link.label);
  }
  return r;
}

MaterialRanges IdentificationResult::Ranges(std::optional<EstimatorKind> kind,
                                            const RangeOptions& bounds) const {
  std::vector<LabeledEstimate> values;
  for (const LinkIdentification& link : links) {
    LabeledEstimate v{link.deflection.link.label, link.value};
    if (kind) {
      const SignalEstimate* s = link.Find(*kind);
      if (s) {
        v.value = s->dominant;
      } else {
        v.value.status = EstimateStatus::kFailed;
      }
    }
    values.push_back(std::move(v));
  }
  return ComputeRanges(values, bounds);
}

void IdentifyOptions::Validate() const {
  if (release_time_s) {
    CheckThat(std::isfinite(*release_time_s), "release_time_s", "a finite time in s",
              *release_time_s);
  }
  CheckNonNegative("window_s", window_s);
  CheckNested("estimation", estimation);
  CheckNested("release", release);
  CheckNested("deflection", deflection);
  CheckNested("outliers", outliers);
  CheckNested("joint", joint);
  CheckNested("branch_modes", branch_modes);
}

void RangeOptions::Validate() const {
  CheckPositive("max_frequency_relative_std", max_frequency_relative_std);
  CheckPositive("max_damping_relative_std", max_damping_relative_std);
}

const char* ToString(JointPolesOutcome outcome) {
  switch (outcome) {
    case JointPolesOutcome::kOff:
      return "off";
    case JointPolesOutcome::kTooFewLinks:
      return "too_few_links";
    case JointPolesOutcome::kNoPoles:
      return "no_poles";
    case JointPolesOutcome::kApplied:
      return "applied";
  }
  return "?";
}

namespace {

// Throws when no marker of the list has a trajectory (nothing could be measured: most likely the
// wrong list); warns of tracks the list does not name.
void CheckMarkersTracked(const Trajectories& trajectories, const std::vector<MarkerLink>& markers,
                         const std::string& source) {
  std::set<int> listed;
  int tracked = 0;
  for (const MarkerLink& m : markers) {
    listed.insert(m.id);
    tracked += trajectories.Find(m.id) != nullptr;
  }
  if (tracked == 0) {
    std::string ids;
    for (const MarkerTrack& t : trajectories.tracks) {
      ids += (ids.empty() ? "" : ", ") + std::to_string(t.marker);
    }
    throw InputError(source, "",
                     fmt::format("none of the {} markers of the marker list has a trajectory "
                                 "(the trajectories hold markers {})",
                                 markers.size(), ids));
  }
  for (const MarkerTrack& track : trajectories.tracks) {
    if (!listed.count(track.marker)) {
      spdlog::warn("{}: marker {} is not in the marker list; it is ignored", source, track.marker);
    }
  }
}

// The free decay: frames [first, end) from the release, to the end or `window_s` long.
struct FreeDecay {
  ReleaseDetection release;
  int first = 0, end = 0;
};

FreeDecay FindFreeDecay(const Trajectories& trajectories, const IdentifyOptions& options,
                        const std::string& source) {
  FreeDecay decay;
  const int n = trajectories.frame_count();
  if (options.release_time_s) {
    decay.first = FrameAtOrAfter(trajectories, *options.release_time_s);
    if (decay.first >= n) {
      throw InputError(source, "",
                       fmt::format("the release time {:.3f} s is after the last frame "
                                   "({:.3f} s)",
                                   *options.release_time_s, trajectories.times_s.back()));
    }
    decay.release.outcome = ReleaseOutcome::kGiven;
    decay.release.frame_index = decay.first;
    decay.release.time_s = trajectories.times_s[decay.first];
    decay.release.note = fmt::format("release given at {:.3f} s", *options.release_time_s);
  } else {
    decay.release = DetectRelease(trajectories, options.release);
    decay.first = decay.release.frame_index;
  }
  decay.end = n;
  if (options.window_s > 0) {
    decay.end = std::min(
        n, FrameAtOrAfter(trajectories, trajectories.times_s[decay.first] + options.window_s));
  }
  return decay;
}

// The chosen estimator, then (when comparing) every other one.
std::vector<EstimatorKind> EstimatorsToRun(const IdentifyOptions& options) {
  std::vector<EstimatorKind> kinds = {options.estimator};
  if (options.compare_estimators) {
    for (EstimatorKind k : AllEstimators()) {
      if (k != options.estimator) kinds.push_back(k);
    }
  }
  return kinds;
}

// Every link's deflection over the free decay, read by every estimator in `kinds`; a link with no
// signal keeps its reason as a kMissingMarker value.
std::vector<LinkIdentification> EstimateLinks(const Trajectories& trajectories,
                                              const std::vector<MarkerLink>& markers,
                                              const FreeDecay& decay,
                                              const std::vector<EstimatorKind>& kinds,
                                              const IdentifyOptions& options) {
  std::vector<LinkIdentification> out;
  const std::vector<DeflectionLink> links = LinksFromMarkers(markers, options.include_root);
  for (DeflectionSignal& deflection :
       ComputeDeflectionSignals(trajectories, links, decay.first, decay.end, options.deflection)) {
    LinkIdentification link;
    if (!deflection.ok()) {
      link.value.status = EstimateStatus::kMissingMarker;
      link.value.message = deflection.problem;
    } else {
      for (EstimatorKind kind : kinds) {
        link.estimates.push_back(EstimateModes(deflection.signal, kind, options.estimation));
      }
      link.value = link.estimates.front().dominant;
    }
    link.deflection = std::move(deflection);
    out.push_back(std::move(link));
  }
  return out;
}

// The damped sinusoid fit's estimate of every link it measured, re-read on joint poles where
// the link's record supports them (all of them with choose_per_link off).
void ApplyJointPoles(const IdentifyOptions& options, IdentificationResult& out) {
  constexpr EstimatorKind kFit = EstimatorKind::kDampedSinusoidFit;
  std::vector<SignalEstimate*> estimates;
  std::vector<SampledSignal> signals;
  std::vector<LinkIdentification*> links;
  for (LinkIdentification& link : out.links) {
    link.poles.own.status = link.poles.joint.status = EstimateStatus::kFailed;
    for (SignalEstimate& e : link.estimates) {
      if (e.estimator != kFit || e.dominant.status != EstimateStatus::kOk) continue;
      estimates.push_back(&e);
      signals.push_back(link.deflection.signal);
      links.push_back(&link);
      link.poles.own = e.dominant;
      link.poles.why = "own fit (per link)";
    }
  }
  if (!options.joint_poles) return;
  if (signals.size() < 2) {
    out.joint_poles = JointPolesOutcome::kTooFewLinks;
    out.joint_poles_note =
        fmt::format("joint poles: {} link measured, nothing to join", signals.size());
    for (LinkIdentification* link : links) link->poles.why = "own fit: no other link to share";
    return;
  }
  JointPoles joint = EstimateJointPoles(signals, options.estimation, options.joint);
  out.joint_poles_note = joint.message;
  if (!joint.ok) {
    out.joint_poles = JointPolesOutcome::kNoPoles;
    for (LinkIdentification* link : links) link->poles.why = "own fit: the joint fit found no mode";
    return;
  }
  out.joint_poles = JointPolesOutcome::kApplied;
  std::vector<LinkModelChoice> choices;
  if (options.choose_per_link) {
    std::vector<const DampedSinusoidFit*> own;
    for (SignalEstimate* e : estimates) own.push_back(&*e->fit);
    choices = ChooseLinkModels(signals, own, joint.fit);
  }
  int shared = 0;
  for (size_t i = 0; i < signals.size(); ++i) {
    SignalEstimate& e = joint.links[i];
    if (e.fit) {
      const SearchBand band = BandOf(options.estimation, e.duration_s, signals[i].dt);
      links[i]->modes =
          ModeShares(*e.fit, e.duration_s,
                     std::max(band.min_hz, options.estimation.min_periods / e.duration_s),
                     band.max_hz, options.estimation.max_damping_ratio);
    }
    // The stack's standard deviations widened by this link's own record of the shared mode.
    WidenBySharedMisfit(*estimates[i], e);
    LinkPolesUse& use = links[i]->poles;
    use.joint = e.dominant;
    if (e.dominant.status != EstimateStatus::kOk) {
      use.why = "own fit: no joint mode";
      continue;
    }
    use.why = choices.empty() ? "shared poles (forced: --joint-poles)" : choices[i].reason;
    if (!choices.empty() && !choices[i].joint) continue;
    ++shared;
    use.shared = true;
    const std::string& own = estimates[i]->dominant.message;
    e.dominant.message = own.empty() ? "joint poles" : own + "; joint poles";
    *estimates[i] = std::move(e);
    if (estimates[i] == &links[i]->estimates.front()) links[i]->value = estimates[i]->dominant;
  }
  out.joint_poles_note +=
      fmt::format("; {} of {} links read the shared poles{}", shared, signals.size(),
                  choices.empty() ? " (forced)" : ", the others their own fit (BIC per link)");
}

// Every link carrying joint poles gets its branch mode (detail/branch_modes.h); its parent
// link is the one whose child is its parent marker.
void AssignBranchModes(const IdentifyOptions& options, IdentificationResult& out) {
  // The joint poles are the damped sinusoid fit's: another estimator's values stay as read.
  if (options.estimator != EstimatorKind::kDampedSinusoidFit) return;
  std::vector<std::vector<LinkModeShare>> shares;
  std::vector<LinkIdentification*> links;
  for (LinkIdentification& link : out.links) {
    if (link.modes.empty()) continue;
    shares.push_back(link.modes);
    links.push_back(&link);
  }
  std::vector<int> parent(links.size(), -1);
  for (size_t i = 0; i < links.size(); ++i) {
    for (size_t j = 0; j < links.size(); ++j) {
      if (links[j]->deflection.link.child == links[i]->deflection.link.parent) parent[i] = j;
    }
  }
  const std::vector<BranchMode> modes = ChooseBranchModes(shares, parent, options.branch_modes);
  for (size_t i = 0; i < links.size(); ++i) {
    LinkIdentification& link = *links[i];
    link.modes = std::move(shares[i]);
    link.branch_mode = modes[i];
    // The dominant mode itself: the link's value as read (own fit or shared, widened deviations).
    const SignalEstimate* fit = link.Find(EstimatorKind::kDampedSinusoidFit);
    if (modes[i].strongest && fit && fit->dominant.status == EstimateStatus::kOk) {
      link.branch_mode.value = fit->dominant;
      for (int c = 0; c < 2 && c < static_cast<int>(fit->per_channel.size()); ++c) {
        link.branch_mode.planes[c] = fit->per_channel[c];
      }
    }
  }
}

}  // namespace

IdentificationResult IdentifyMaterials(const Trajectories& input,
                                       const std::vector<MarkerLink>& markers,
                                       const IdentifyOptions& options, const std::string& source) {
  options.Validate();
  IdentificationResult out;
  // A tracker jump would pass for the release and put a spike in every spectrum: gaps first.
  Trajectories trajectories = input;
  if (options.remove_outliers) {
    out.outliers = RemoveTrackOutliers(trajectories, options.outliers);
    if (out.outliers.removed > 0) spdlog::info("{}: {}", source, out.outliers.note);
  }
  out.estimator = options.estimator;
  if (trajectories.frame_count() < 2) {
    throw InputError(source, "", "expected at least 2 frames of trajectories");
  }
  CheckMarkersTracked(trajectories, markers, source);
  const int n = trajectories.frame_count();
  out.frame_rate_hz = (n - 1) / (trajectories.times_s.back() - trajectories.times_s.front());

  // Only the free decay after the release follows the modal model the estimators fit.
  const FreeDecay decay = FindFreeDecay(trajectories, options, source);
  out.release = decay.release;
  out.window_start_s = trajectories.times_s[decay.first];
  out.window_end_s = trajectories.times_s[std::max(decay.first, decay.end - 1)];

  out.estimators = EstimatorsToRun(options);
  out.links = EstimateLinks(trajectories, markers, decay, out.estimators, options);
  // The tree's modes are shared by every link: read the measured links on poles fitted to all.
  ApplyJointPoles(options, out);
  // Each branch its own mode: the joint pole it moves in most relative to its parent.
  AssignBranchModes(options, out);
  return out;
}

namespace {

std::string Value(double x, const char* format) {
  return std::isfinite(x) ? fmt::format(fmt::runtime(format), x) : "-";
}

}  // namespace

std::string FormatRanges(const MaterialRanges& r, const std::string& name) {
  if (r.measured == 0) {
    return fmt::format("{:<22} no link measured ({} links)", name, r.links);
  }
  std::string out = fmt::format(
      "{:<22} f {:.2f}~{:.2f} Hz   zeta {:.3f}~{:.3f}   ({} of {} links measured", name,
      r.min_frequency_hz, r.max_frequency_hz, r.min_damping, r.max_damping, r.measured, r.links);
  if (r.uncertain.empty()) return out + ")";
  std::string labels;
  for (const std::string& label : r.uncertain) labels += (labels.empty() ? "" : ", ") + label;
  return out + fmt::format(
                   "; {} uncertain, left out: {}; every value: f {:.2f}~{:.2f} Hz, zeta "
                   "{:.3f}~{:.3f})",
                   r.uncertain.size(), labels, r.all_min_frequency_hz, r.all_max_frequency_hz,
                   r.all_min_damping, r.all_max_damping);
}

std::string FormatLinkTable(const IdentificationResult& result) {
  std::string out = fmt::format("{:<14} {:<14} {:>16} {:>16}", "link", "status", "f (Hz)", "zeta");
  std::vector<EstimatorKind> others;
  if (!result.links.empty()) {
    for (const SignalEstimate& e : result.links.front().estimates) {
      if (e.estimator != result.estimator) others.push_back(e.estimator);
    }
  }
  for (EstimatorKind k : others) out += fmt::format("   {:>24}", ToString(k));
  out += "\n";
  for (const LinkIdentification& link : result.links) {
    const ModalEstimate& v = link.value;
    std::string f = Value(v.frequency_hz, "{:.4f}");
    std::string z = Value(v.damping_ratio, "{:.4f}");
    if (std::isfinite(v.frequency_std_hz)) f += Value(v.frequency_std_hz, "±{:.4f}");
    if (std::isfinite(v.damping_std)) z += Value(v.damping_std, "±{:.4f}");
    out += fmt::format("{:<14} {:<14} {:>16} {:>16}", link.deflection.link.label,
                       ToString(v.status), f, z);
    for (EstimatorKind k : others) {
      const SignalEstimate* e = link.Find(k);
      const std::string cell = e ? Value(e->dominant.frequency_hz, "{:.3f}") + " / " +
                                       Value(e->dominant.damping_ratio, "{:.4f}")
                                 : "-";
      out += fmt::format("   {:>24}", cell);
    }
    if (v.status != EstimateStatus::kOk && !v.message.empty()) out += "   " + v.message;
    out += "\n";
  }
  return out;
}

std::string FormatSummary(const IdentificationResult& result, const RangeOptions& bounds) {
  std::string out = FormatLinkTable(result) + "\n";
  out += fmt::format(
      "Ranges (paper Table IV), over values known to {:.0f}% (frequency) and {:.0f}% (damping), "
      "one standard deviation:\n",
      100 * bounds.max_frequency_relative_std, 100 * bounds.max_damping_relative_std);
  for (EstimatorKind kind : result.estimators) {
    const MaterialRanges ranges = kind == result.estimator ? result.Ranges(std::nullopt, bounds)
                                                           : result.Ranges(kind, bounds);
    out += "  " + FormatRanges(ranges, ToString(kind)) + "\n";
  }
  return out;
}

}  // namespace simtree::identification
