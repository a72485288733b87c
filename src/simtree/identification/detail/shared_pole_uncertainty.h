#pragma once
// The uncertainty of a link's reading on the shared poles, from that link's own record (issue 23).
//
// A joint pole's standard deviation is the whole stack's (joint_poles.h): every link's samples pin
// it, far better than its bias for any one link is known (a close pair merged into one pole,
// another link's mode standing in for this link's). The link's own fit reads the same quantity,
// the link's dominant mode, from this link alone, with its own standard deviation. If the shared
// value were right for this link, the two would differ by d with E[d^2] = s_own^2 + s_shared^2;
// what d^2 holds beyond that is the shared value's bias for this link,
// b^2 = max(0, d^2 - s_own^2 - s_shared^2) (the moment estimate of a random-effects
// meta-analysis, here of one link), and the reading's variance is s_shared^2 + b^2. When the two
// fits name different modes dominant, d is their distance: the record does not settle which
// mode it is, and the shared reading says so. Frequency and damping each on their own; the
// values are left as they are.

#include "simtree/identification/estimators.h"

namespace simtree::identification {

// Widens the standard deviations of `shared` (a link's reading on the joint poles: dominant and
// each plane's) by their discrepancy with `own` (the same link's own fit, estimator (c)): the
// dominant against the dominant, each plane against the same plane. A value whose own
// counterpart is missing keeps its deviations.
void WidenBySharedMisfit(const SignalEstimate& own, SignalEstimate& shared);

}  // namespace simtree::identification
