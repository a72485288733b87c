#pragma once
// Materials for branches that carry no marker (paper III-D: "interpolating from the known
// material properties according to their lengths and thicknesses").
//
// Frequency: a cantilever's first frequency scales as f ∝ r / L^2 (Euler-Bernoulli: f ∝
// sqrt(EI / (mu L^4)) with I ∝ r^4 and mu ∝ r^2). In log space that is a line, fitted on the
// measured branches: log f = a + b log(r / L^2), or with free exponents log f = a + b log r +
// c log L when there are enough branches, or just the (log) median when there are few or they do
// not vary. A fourth model takes the hierarchy instead of the size: a branch swings at the
// dominant frequency of the nearest measured branch it hangs from (its nearest measured
// ancestor; the median where it hangs from none), because a pull test's modes live in subtrees:
// on synthetic pull tests the unmarked branches' true frequencies fall into a few whole-tree
// modes, by the first- or second-level branch they hang from, not by their size
// (docs/simready.md, "Interpolation"). Leave-one-out error picks among the four, so a tree
// whose branches all swing near one frequency (a whole-tree mode dominates; real trees often do)
// is not forced onto the cantilever law; ties keep the earlier (simpler) model, in the order
// median, ancestor, cantilever, two slopes. Predictions are clamped to the measured range (paper:
// "unknown parameters should be in the range of known parameters").
//
// Damping: the median of the measured branches of the same level, else of the nearest level with
// measurements.
//
// Weights (InterpolationOptions::weight_by_uncertainty): each measured value counts by its inverse
// variance (sample_weights.h: 1 / relative sd^2, floored at the median relative sd), frequency
// and damping each by their own deviation: weighted least squares for the size laws, weighted
// medians for the median, the damping per level and the ancestor model's fallback, and the
// leave-one-out error that chooses among the models a weighted mean.
//
// r is the branch's base radius (its thickness where it bends most), L its length.

#include <limits>
#include <string>
#include <vector>

#include "simtree/core/tree.h"

namespace simtree::simready {

enum class FrequencyModelKind { kMedian, kNearestMeasuredAncestor, kCantilever, kLengthAndRadius };
// "median", "nearest_measured_ancestor", "cantilever", "length_and_radius"
const char* ToString(FrequencyModelKind kind);

// One measured branch: its dominant frequency and damping, with their standard deviations (NaN:
// not given).
struct BranchSample {
  int branch = 0;
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;
  double frequency_std_hz = std::numeric_limits<double>::quiet_NaN();
  double damping_std = std::numeric_limits<double>::quiet_NaN();
};

struct InterpolationOptions {
  // Fewest measured branches for the one-slope cantilever fit (>= 3: a line fitted with one
  // branch left out), and for the two-slope fit (>= 4).
  int min_branches_cantilever = 3;
  int min_branches_two_slopes = 6;
  bool clamp_to_measured = true;  // predictions clamped to the measured frequency range
  // Each measured value weighted by its inverse variance (above); false: all alike.
  bool weight_by_uncertainty = false;

  // Throws InputError naming the field for a value out of range.
  void Validate() const;
};

struct InterpolationModel {
  FrequencyModelKind kind = FrequencyModelKind::kMedian;
  std::vector<double> coefficients;                       // a (the median for kMedian and the
                                                          // ancestor model), then the slopes
  double min_frequency_hz = 0.0, max_frequency_hz = 0.0;  // the measured range
  // Mean absolute leave-one-out error of log f over the measured branches (NaN with < 2). The
  // mean absolute error, not the RMS: a pull test leaves a few branches at a local mode far from
  // the rest, and squared errors let those few pick a size law whose prediction lies between the
  // modes, right for no branch (docs/simready.md, "Interpolation").
  double leave_one_out_log_error = 0.0;
  std::vector<double> level_damping;  // per level, NaN where no branch of that level is measured
  double median_damping = 0.0;
  int measured = 0;
  bool clamp = true;
  bool weighted = false;  // fitted with inverse-variance weights

  // The measured dominant frequency of every branch of the tree (NaN: not measured), for the
  // ancestor model.
  std::vector<double> measured_frequency_hz;

  // Predicted frequency of `branch` of the tree the model was fitted on (clamped when `clamp`).
  double Frequency(const Tree& tree, int branch) const;
  // Predicted frequency of a branch of base radius r and length L, by the size models (the
  // ancestor model gives its median here: a branch of no known place in the tree hangs from
  // none).
  double Frequency(double radius_m, double length_m) const;
  double Damping(int level) const;
  // "log f = -0.12 + 0.31 log(r/L^2), leave-one-out 4.1%, 7 branches".
  std::string Describe() const;
};

// Fits the model on `samples` (branches of `tree`). Throws InputError when there is none.
InterpolationModel FitInterpolationModel(const Tree& tree, const std::vector<BranchSample>& samples,
                                         const InterpolationOptions& options = {});

}  // namespace simtree::simready
