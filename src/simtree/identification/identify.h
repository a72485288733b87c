#pragma once
// Material identification from a pull test (paper III-C): marker trajectories and their links in,
// natural frequency and damping ratio of every link out, with every estimator's reading beside
// the chosen one and a Table IV-style summary.
//
//   trajectories ──► release ──► free-decay window ──► deflection per link ──► estimators

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "simtree/identification/deflection.h"
#include "simtree/identification/estimators.h"
#include "simtree/identification/release.h"
#include "simtree/identification/track_outliers.h"
#include "simtree/io/capture.h"
#include "simtree/io/trajectories.h"

namespace simtree {

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
};

struct LinkIdentification {
  DeflectionSignal deflection;
  ModalEstimate value;                    // the chosen estimator's dominant mode
  std::vector<SignalEstimate> estimates;  // the chosen estimator first, then the others

  const SignalEstimate* Find(EstimatorKind kind) const;
  bool measured() const { return value.status == EstimateStatus::kOk; }
};

// Ranges over the links with a value (paper Table IV: "Natural frequency f (Hz)", "Damping
// ratio"). NaN when no link has one.
struct MaterialRanges {
  int links = 0;
  int measured = 0;
  double min_frequency_hz = std::numeric_limits<double>::quiet_NaN();
  double max_frequency_hz = std::numeric_limits<double>::quiet_NaN();
  double min_damping = std::numeric_limits<double>::quiet_NaN();
  double max_damping = std::numeric_limits<double>::quiet_NaN();
};

struct IdentificationResult {
  TrackOutlierReport outliers;  // tracker jumps removed before the rest
  ReleaseDetection release;     // as detected (or as given)
  double window_start_s = 0.0, window_end_s = 0.0;
  double frame_rate_hz = 0.0;
  EstimatorKind estimator = kDefaultEstimator;
  std::vector<LinkIdentification> links;

  MaterialRanges Ranges(std::optional<EstimatorKind> kind = std::nullopt) const;
};

// Every link of `markers` (markers.json) identified from `trajectories`. A link whose markers
// are not in the trajectories is reported with status kMissingMarker, not dropped; markers in the
// trajectories but not in the list are ignored (with a warning). `source` names the trajectories
// in messages. Throws InputError when no marker of the list has a trajectory at all.
IdentificationResult IdentifyMaterials(const Trajectories& trajectories,
                                       const std::vector<MarkerLink>& markers,
                                       const IdentifyOptions& options = {},
                                       const std::string& source = "<trajectories>");

// The paper's Table IV row for one tree, plus the counts: "species  f_min~f_max zeta_min~zeta_max".
std::string FormatRanges(const MaterialRanges& ranges, const std::string& name);
// A per-link table (label, status, f, zeta with their standard deviations, and every estimator).
std::string FormatLinkTable(const IdentificationResult& result);

}  // namespace simtree
