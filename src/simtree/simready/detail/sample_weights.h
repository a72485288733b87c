#pragma once
// Inverse-variance weights for the measured branches the interpolation is fitted on.
//
// Each value's weight is 1 / s^2 with s its relative standard deviation (sd / value: the fit works
// on log f, where a relative deviation is the deviation), floored at the median s of the values
// that have one, so that one value the identification reads unusually tightly does not outweigh
// the rest: the floor comes from the record itself, not a constant. A value without a deviation
// (an estimator that gives none) counts as a typical one (the floor); a value whose deviation is
// infinite (its covariance broke down) as the least certain one given. Weights are scaled so the
// largest is 1; with no deviation given at all every weight is 1 (the unweighted fit).

#include <vector>

namespace simtree::simready {

// `values` and `stds` of the same length; stds NaN where not given.
std::vector<double> InverseVarianceWeights(const std::vector<double>& values,
                                           const std::vector<double>& stds);

// The value at half the total weight (the mean of the two values either side when the half falls
// exactly between them, so equal weights give the plain median). NaN when empty.
double WeightedMedian(const std::vector<double>& values, const std::vector<double>& weights);

}  // namespace simtree::simready
