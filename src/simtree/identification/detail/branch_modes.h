#pragma once
// Each measured branch its own mode (issue 23, part 4).
//
// A link's dominant mode is the strongest peak of its whole signal. On a tree that is mostly a
// whole-tree sway, while what a branch does on its own (the per-branch modal model of paper
// Fig. 8, synth's per-branch truth) may be another mode, the one in which it moves most relative
// to its parent. Here every joint pole (joint_poles.h) gets, per link, its strength (estimator
// (c)'s rule: amplitude at the release times the integral of its envelope over the record), its
// share (over the link's strongest pole's) and its participation: the link's share over the parent
// link's share of the same pole. A pole the parent carries as strongly as the child has
// participation about 1 (the child rides on it); one the child carries far more than its parent
// looks like the child's own. The most participating pole among those the link carries with at
// least `min_share` is reported beside the dominant one.
//
// Which one the branch gets is `by_participation` (default: the dominant mode). Measured on the
// FEM synth (3 presets x seeds 1-3, 2.5 mm tracker error, docs/identification.md "Each branch
// its own mode"): by participation the measured branches' median error against their own FEM
// truth rose from 1.63% to 13.8% (min_share 0.3). A link and its parent carry the tree's first
// few modes in similar shares, and a link from the trunk marker is measured against the fixed
// camera, so the trunk's tilt is in its signal and its parent's alike.

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "simtree/identification/estimators.h"

namespace simtree::identification {

struct BranchModeOptions {
  // The branch gets the most participating pole (true) or the link's dominant mode (false).
  bool by_participation = false;
  // Poles a link carries with less than this share of its strongest pole's strength are not
  // candidates (noise and the tails of stronger modes).
  double min_share = 0.3;
  // Participation is capped here so a pole the parent does not carry at all cannot win on a
  // vanishing denominator alone.
  double max_participation = 10.0;

  // Throws InputError naming the field for a value out of range.
  void Validate() const;
};

// One joint pole as one link carries it.
struct LinkModeShare {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double frequency_hz = kNaN, damping_ratio = kNaN;
  double frequency_std_hz = kNaN, damping_std = kNaN;
  double amplitude = kNaN;  // at the release, both planes, signal units
  std::array<double, 2> plane_amplitude = {kNaN, kNaN};
  double strength = kNaN;       // spectral peak over the record
  double share = kNaN;          // strength over the link's strongest pole's
  double participation = kNaN;  // share over the parent link's share (NaN: none)
};

// The poles of `fit` (a link's reading of the joint poles) inside [min_hz, max_hz] and damped
// below `max_damping_ratio`, strongest first, with their shares; no participation yet.
std::vector<LinkModeShare> ModeShares(const DampedSinusoidFit& fit, double record_s, double min_hz,
                                      double max_hz, double max_damping_ratio);

struct BranchMode {
  ModalEstimate value;  // status kFailed when not chosen
  std::array<ModalEstimate, 2> planes;
  double participation = std::numeric_limits<double>::quiet_NaN();
  bool strongest = false;  // the link's strongest pole: its dominant mode is the branch's
  // The most participating candidate pole (reported whichever is chosen; NaN without a parent).
  double most_participating_hz = std::numeric_limits<double>::quiet_NaN();
  std::string why;  // for a person
};

// `links[i]`: link i's mode shares; `parent[i]`: the index of its parent link in `links` (-1:
// none measured). Fills each share's participation and returns each link's branch mode.
std::vector<BranchMode> ChooseBranchModes(std::vector<std::vector<LinkModeShare>>& links,
                                          const std::vector<int>& parent,
                                          const BranchModeOptions& options = {});

}  // namespace simtree::identification
