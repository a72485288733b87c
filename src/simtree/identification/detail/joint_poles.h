#pragma once
// Poles shared by every link of a tree (the poly-reference idea of operational modal analysis).
//
// A tree's modes are global: every link swings at the same frequencies with the same damping,
// only in different proportions. One link alone cannot tell two modes a few percent apart from
// one decaying mode when their beat is longer than the record; links that mix them in different
// ratios can. Here the links' records are stacked (each scaled to unit RMS, so each link weighs
// the same), reduced to their strongest principal components, and estimator (c)'s fit
// (FitDampedSinusoids) finds the poles of those components: how many modes (BIC) and where to
// start. The poles are then refined on every link's valid samples at once (variable projection:
// Levenberg-Marquardt on the poles, each link's offsets and amplitudes by linear least squares),
// so neither filled gaps nor the components left out bias them. Each link then gets its own
// amplitude of each joint pole (least squares of that pole alone on its valid samples: in a joint
// least squares close poles can cancel each other with large amplitudes) and its dominant mode by
// estimator (c)'s rule (ReadFittedModes).
//
// Gaps: the principal components need every sample, so each link's gaps are filled by linear
// interpolation for the starting fit only. Standard deviations are the refinement's (its
// Jacobian with the amplitudes projected out, inflated for lag-1 correlated residuals): one per
// pole, shared by every link that reads that pole; `identify` widens them per link by what the
// link's own fit says (shared_pole_uncertainty.h).
//
// Merged poles: BIC on the components may take two close modes for one pole, so every pole is
// offered split in two and refined on every link; the split is kept when the joint BIC falls
// (SplitMergedPoles in joint_poles.cc).
//
// `identify` reads the links this way by default (`--per-link` turns it off); why, with the
// figures: docs/identification.md, "Joint poles across links".

#include <string>
#include <vector>

#include "simtree/identification/detail/sampled_signal.h"
#include "simtree/identification/estimators.h"

namespace simtree::identification {

struct JointPolesOptions {
  int components = 6;  // principal components of the stacked links the poles are fitted on
  // Most modes of the joint model (chosen by BIC; it replaces EstimatorOptions::max_modes for
  // the joint fit). Error-free records use many (the release excites the higher modes too), and
  // too low a limit leaves room for a spurious pole.
  int max_modes = 20;
  // Offer every pole split in two, refined on every link, kept when the joint BIC falls
  // (SplitMergedPoles in joint_poles.cc); a split closer than `min_split` (relative frequency)
  // is none.
  bool split_merged_poles = true;
  double min_split = 0.002;

  // Throws InputError naming the field for a value out of range.
  void Validate() const;
};

struct JointPoles {
  bool ok = false;      // poles were fitted (false: `message` says why not)
  std::string message;  // why there are no joint poles, or what was fitted
  int splits = 0;       // poles added by splitting merged ones
  // The fit on the principal components, its poles (and their standard deviations) replaced by
  // the refined ones; its amplitudes are the components' before refinement.
  DampedSinusoidFit fit;
  // Per input signal, in order: estimator (c)'s reading with the joint poles and the link's own
  // amplitudes (fit holds that link's model).
  std::vector<SignalEstimate> links;
};

// `signals`: the links' records, all on the same sample grid (same start, step and length).
// Throws std::invalid_argument when they are not.
JointPoles EstimateJointPoles(const std::vector<SampledSignal>& signals,
                              const EstimatorOptions& estimation,
                              const JointPolesOptions& options = {});

}  // namespace simtree::identification
