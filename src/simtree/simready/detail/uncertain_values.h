#pragma once
// Measured values `build` should not trust as they are (issue 23: "build weighting or flagging
// values by" their standard deviations).
//
// A measured branch's value is flagged uncertain when
//  - its relative standard deviation is over a bound: the frequency's (sd / f) over
//    max_frequency_relative_std, or the damping ratio's over max_damping_relative_std; or it has
//    none where the others have one (the fit's covariance broke down: build.cc makes it infinite),
//    whatever the bound; or
//  - its frequency lies far from what the other measured branches predict, given both
//    deviations: z = |log f - log f_pred| / sqrt(s^2 + s_pred^2) over max_z, with f_pred the
//    interpolation fitted without this branch, s its relative sd and s_pred the interpolation's
//    own error (its leave-one-out mean absolute error of log f, times sqrt(pi / 2), the standard
//    deviation of a normal error of that mean absolute value). Needs >= 3 measured branches.
// A flagged frequency is left out of the interpolation's frequency fit, a flagged damping ratio
// out of its damping; either is replaced by the interpolation when that is the more certain: for
// a frequency, the interpolation's error (as above) smaller than the value's own relative sd, or
// than its distance from the prediction; for a damping ratio, the spread of the unflagged
// branches' damping ratios (1.4826 x their median absolute log deviation) smaller than its
// relative sd.

#include <limits>
#include <string>
#include <vector>

#include "simtree/core/tree.h"
#include "simtree/simready/detail/interpolation.h"

namespace simtree::simready {

// The defaults are what measured better on synth's FEM pull tests (docs/simready.md, "Uncertain
// measured values"): the frequency's own deviation only; the damping bound and the z-score are
// there (infinite: off) because they measured worse or mixed there.
struct UncertaintyOptions {
  bool flag = true;     // look for uncertain values at all
  bool replace = true;  // flagged values take the interpolation's when more certain
  // 10%: the bar for a branch's value; a frequency not known to 10% cannot meet it.
  double max_frequency_relative_std = 0.10;
  double max_damping_relative_std = std::numeric_limits<double>::infinity();
  double max_z = std::numeric_limits<double>::infinity();  // distance from the others, in sds

  // Throws InputError naming the field for a value out of range.
  void Validate() const;
};

// One measured branch's verdict.
struct SampleVerdict {
  std::string why;            // empty: trusted
  double predicted_hz = 0.0;  // the interpolation without it (NaN with < 3 branches)
  double z = 0.0;             // its frequency's z-score against that prediction (NaN: none)
  double effective_relative_error = 0.0;  // the larger of its relative sd and its log distance
  bool frequency_flag = false, damping_flag = false;
};

// A verdict per sample, in the order of `samples`.
std::vector<SampleVerdict> JudgeSamples(const Tree& tree, const std::vector<BranchSample>& samples,
                                        const UncertaintyOptions& options,
                                        const InterpolationOptions& interpolation);

// Whether the flagged frequency is less certain than the interpolation `model` (fitted on the
// trusted frequencies) predicts: false when the frequency is not flagged.
bool FrequencyIsLessCertain(const SampleVerdict& verdict, const InterpolationModel& model);

// Whether the flagged damping ratio of `sample` is less certain than the spread of the trusted
// damping ratios: false when the damping ratio is not flagged.
bool DampingIsLessCertain(const SampleVerdict& verdict, const BranchSample& sample,
                          const std::vector<BranchSample>& trusted);

}  // namespace simtree::simready
