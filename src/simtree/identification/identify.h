#pragma once
// Material identification from a pull test (paper III-C): marker trajectories and their links in,
// natural frequency and damping ratio of every link out, with every estimator's reading beside
// the chosen one and a Table IV-style summary.
//
//   trajectories ──► release ──► free-decay window ──► deflection per link ──► estimators
//
// Usage:
//   const simtree::Trajectories tracks = simtree::ReadTrajectoriesCsv("tracks/trajectories.csv");
//   const auto markers = simtree::ReadMarkersJson("scene/pull/markers.json");
//   const simtree::identification::IdentificationResult result =
//       simtree::identification::IdentifyMaterials(tracks, markers, {});
//   simtree::identification::WriteMaterialsJson(
//       simtree::identification::MaterialsFromIdentification(result, "trajectories.csv"),
//       "materials.json");

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "simtree/identification/detail/branch_modes.h"
#include "simtree/identification/detail/deflection.h"
#include "simtree/identification/detail/joint_poles.h"
#include "simtree/identification/detail/release.h"
#include "simtree/identification/detail/track_outliers.h"
#include "simtree/identification/estimators.h"
#include "simtree/io/capture.h"
#include "simtree/io/trajectories.h"

namespace simtree::identification {

struct IdentifyOptions {
  // The estimator whose values are chosen; with `compare_estimators` the others run too
  // (reported, not used).
  EstimatorKind estimator = kDefaultEstimator;
  bool compare_estimators = true;
  EstimatorOptions estimation;  // the estimators' band, limits and fit (estimators.h)
  ReleaseOptions release;       // release detection (detail/release.h)
  // The release time (s, on the trajectories' clock) when known; otherwise it is detected.
  std::optional<double> release_time_s;
  double window_s = 0.0;         // seconds of free decay kept after the release (0: to the end)
  DeflectionOptions deflection;  // the links' planes and rest pose (detail/deflection.h)
  bool include_root = true;      // give the root (trunk) marker's displacement a value too
  // Turn tracker jumps into gaps before anything else (track_outliers.h).
  bool remove_outliers = true;
  TrackOutlierOptions outliers;  // the tracker-jump test (detail/track_outliers.h)
  // Replace the damped sinusoid fit's values of the links it measured by a reading on poles
  // fitted to all those links at once (joint_poles.h; a link whose joint reading fails keeps its
  // own). A tree's modes are shared by every link, and links that mix two close modes in
  // different ratios tell them apart where one link cannot (docs/identification.md).
  bool joint_poles = true;
  // With joint poles: each link keeps the joint reading only when its own record supports it
  // (detail/link_model_choice.h: BIC of the shared poles against the link's own fit); a link
  // that rings at its own frequencies keeps its own fit. False: every link reads the joint poles.
  bool choose_per_link = true;
  JointPolesOptions joint;  // the joint fit (detail/joint_poles.h)
  // Each measured branch's own mode among the joint poles (detail/branch_modes.h).
  BranchModeOptions branch_modes;

  // Throws InputError naming the field ("estimation.max_modes") for a value out of range.
  void Validate() const;
};

// What the joint reading across links (IdentifyOptions::joint_poles) did.
enum class JointPolesOutcome {
  kOff,          // IdentifyOptions::joint_poles is false
  kTooFewLinks,  // fewer than 2 links measured by the damped sinusoid fit: nothing to join
  kNoPoles,      // the joint fit found no mode: every link keeps its own fit
  kApplied,      // the measured links read on the joint poles
};
// "off", "too_few_links", "no_poles", "applied".
const char* ToString(JointPolesOutcome outcome);

// Which poles a link's damped sinusoid fit was read on, and why (materials.json "poles").
struct LinkPolesUse {
  bool shared = false;  // the joint poles (else the link's own fit)
  std::string why;      // for a person: the override, or the criterion's numbers
  // Both readings of the fit's dominant mode (kFailed when not made); the joint one's standard
  // deviations widened by its discrepancy with the own (detail/shared_pole_uncertainty.h).
  ModalEstimate own, joint;
};

struct LinkIdentification {
  DeflectionSignal deflection;
  ModalEstimate value;                    // the chosen estimator's dominant mode
  std::vector<SignalEstimate> estimates;  // the chosen estimator first, then the others
  LinkPolesUse poles;                     // the damped sinusoid fit's poles
  // The joint poles as this link carries them (empty without joint poles), and the one its
  // branch moves in most relative to its parent (detail/branch_modes.h; kFailed when none).
  std::vector<LinkModeShare> modes;
  BranchMode branch_mode;

  const SignalEstimate* Find(EstimatorKind kind) const;
  bool measured() const { return value.status == EstimateStatus::kOk; }
};

// Table IV-style ranges must not be set by values the fit could not pin down: a value counts in
// its range only when its relative standard deviation (the estimator's own, estimators.h) is
// within these bounds. A value without one (the spectral estimators give none) always counts.
// The bounds follow from what the ranges are for, not from any truth: a frequency known to 2%
// (twice the 1% the identification aims at) and a damping ratio known to 20% (Table IV's damping
// ranges are 1.4-2.5x wide: a 1-sigma band of +-20% still says where in it a value lies).
struct RangeOptions {
  double max_frequency_relative_std = 0.02;  // frequency's standard deviation over its value
  double max_damping_relative_std = 0.20;    // damping ratio's standard deviation over its value

  // Throws InputError naming the field for a value out of range.
  void Validate() const;
};

// Ranges over the links with a value (paper Table IV: "Natural frequency f (Hz)", "Damping
// ratio"): min/max over the values within the bounds, all_* over every value, and the links
// left out of a range listed as uncertain. NaN when no value counts.
struct MaterialRanges {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  int links = 0;
  int measured = 0;
  RangeOptions bounds;
  int frequency_count = 0, damping_count = 0;  // values inside the bounds
  double min_frequency_hz = kNaN, max_frequency_hz = kNaN;
  double min_damping = kNaN, max_damping = kNaN;
  double all_min_frequency_hz = kNaN, all_max_frequency_hz = kNaN;
  double all_min_damping = kNaN, all_max_damping = kNaN;
  // Labels of measured links whose frequency or damping is outside its bound.
  std::vector<std::string> uncertain;
};

// One link's value as the ranges see it.
struct LabeledEstimate {
  std::string label;
  ModalEstimate value;
};
// `links`: every link (measured or not; only kOk values count).
MaterialRanges ComputeRanges(const std::vector<LabeledEstimate>& links,
                             const RangeOptions& bounds = {});

struct IdentificationResult {
  TrackOutlierReport outliers;  // tracker jumps removed before the rest
  ReleaseDetection release;     // as detected (or as given)
  // The free decay used, s on the trajectories' clock.
  double window_start_s = 0.0, window_end_s = 0.0;
  double frame_rate_hz = 0.0;
  EstimatorKind estimator = kDefaultEstimator;
  std::vector<EstimatorKind> estimators;  // every estimator run, the chosen one first
  std::vector<LinkIdentification> links;
  JointPolesOutcome joint_poles = JointPolesOutcome::kOff;
  std::string joint_poles_note;  // what the joint fit did, for a person (empty when off)

  MaterialRanges Ranges(std::optional<EstimatorKind> kind = std::nullopt,
                        const RangeOptions& bounds = {}) const;
};

// Every link of `markers` (markers.json) identified from `trajectories`. A link whose markers
// are not in the trajectories is reported with status kMissingMarker, not dropped; markers in the
// trajectories but not in the list are ignored (with a warning). `source` names the trajectories
// in messages. Throws InputError when no marker of the list has a trajectory at all.
IdentificationResult IdentifyMaterials(const Trajectories& trajectories,
                                       const std::vector<MarkerLink>& markers,
                                       const IdentifyOptions& options = {},
                                       const std::string& source = "<trajectories>");

// The paper's Table IV row for one tree, plus the counts: "species  f_min~f_max zeta_min~zeta_max",
// and the uncertain links left out (with the range over every value).
std::string FormatRanges(const MaterialRanges& ranges, const std::string& name);
// A per-link table (label, status, f, zeta with their standard deviations, and every estimator).
std::string FormatLinkTable(const IdentificationResult& result);
// What `simtree identify` prints: the link table, then the Table IV row of every estimator run
// (the chosen one first), over the values known to `bounds`.
std::string FormatSummary(const IdentificationResult& result, const RangeOptions& bounds = {});

}  // namespace simtree::identification
