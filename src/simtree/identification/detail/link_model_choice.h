#pragma once
// Per link: the tree's shared poles or the link's own? (issue 23)
//
// Whole-tree modes are shared by every link (joint_poles.h), but a long light branch rings at its
// own frequencies, which no shared pole fits. Each link's record decides, by the Bayesian
// information criterion over that link's residual:
//  - its own fit (estimator (c) alone): K poles, two parameters each, and per channel an offset
//    and two amplitudes per pole;
//  - the shared poles: the ones that explain this link (forward selection by BIC among the joint
//    poles, amplitudes by linear least squares), per channel an offset and two amplitudes per
//    pole, and each pole's two parameters apportioned over the links that select it.
// Both are counted on the same effective sample count, n (1 - rho) / (1 + rho) with rho the lag-1
// autocorrelation of the better-fitting residual (the noise's own correlation: the worse one's
// excess is the misfit under test), as joint_poles.cc counts the stacked residual. A tie goes to
// the shared poles.

#include <string>
#include <vector>

#include "simtree/identification/detail/sampled_signal.h"
#include "simtree/identification/estimators.h"

namespace simtree::identification {

struct LinkModelChoice {
  bool joint = false;  // the shared poles explain the link at least as well
  double own_bic = 0.0, joint_bic = 0.0;
  int own_modes = 0, joint_modes = 0;     // poles each model holds for this link
  double own_rms = 0.0, joint_rms = 0.0;  // residual RMS, signal units
  double effective_samples = 0.0;
  std::string reason;  // for a person: "shared poles: BIC 812.3 <= own 820.1 (...)"
};

// `signals[i]`'s own fit `own[i]` (estimator (c) on that link alone) against the joint poles
// `joint` (EstimateJointPoles' fit). Every link must have an own fit; they are on one grid.
std::vector<LinkModelChoice> ChooseLinkModels(const std::vector<SampledSignal>& signals,
                                              const std::vector<const DampedSinusoidFit*>& own,
                                              const DampedSinusoidFit& joint);

}  // namespace simtree::identification
