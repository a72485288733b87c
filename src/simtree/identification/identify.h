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

#include "simtree/identification/detail/deflection.h"
#include "simtree/identification/detail/joint_poles.h"
#include "simtree/identification/detail/release.h"
#include "simtree/identification/detail/track_outliers.h"
#include "simtree/identification/estimators.h"
#include "simtree/io/capture.h"
#include "simtree/io/trajectories.h"

namespace simtree::identification {

struct IdentifyOptions {
  EstimatorKind estimator = kDefaultEstimator;
  // Run the other estimators too, for comparison (reported, not used).
  bool compare_estimators = true;
  EstimatorOptions estimation;
  ReleaseOptions release;
  // The release time (s, on the trajectories' clock) when known; otherwise it is detected.
  std::optional<double> release_time_s;
  // Seconds of free decay kept after the release (0: to the end of the record).
  double window_s = 0.0;
  DeflectionOptions deflection;
  // Give the root (trunk) marker's displacement a value too.
  bool include_root = true;
  // Tracker jumps are turned into gaps before anything else (track_outliers.h).
  bool remove_outliers = true;
  TrackOutlierOptions outliers;
  // Replace the damped sinusoid fit's values of the links it measured by a reading on poles
  // fitted to all those links at once (joint_poles.h; a link whose joint reading fails keeps its
  // own). On by default: it measures better than each link alone on the synthetic pull tests
  // (docs/identification.md, "Joint poles across links").
  bool joint_poles = true;
  JointPolesOptions joint;
};

struct LinkIdentification {
  DeflectionSignal deflection;
  ModalEstimate value;                    // the chosen estimator's dominant mode
  std::vector<SignalEstimate> estimates;  // the chosen estimator first, then the others

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
  double max_frequency_relative_std = 0.02;
  double max_damping_relative_std = 0.20;
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
  double window_start_s = 0.0, window_end_s = 0.0;
  double frame_rate_hz = 0.0;
  EstimatorKind estimator = kDefaultEstimator;
  std::vector<LinkIdentification> links;
  std::string joint_poles_note;  // with IdentifyOptions::joint_poles: what the joint fit did

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

}  // namespace simtree::identification
