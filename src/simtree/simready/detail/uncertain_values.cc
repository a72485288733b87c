#include "simtree/simready/detail/uncertain_values.h"

#include <cmath>

#include <fmt/format.h>

#include "simtree/core/option_checks.h"
#include "simtree/core/statistics.h"
#include "simtree/core/units.h"

namespace simtree::simready {
namespace {

// A normal error's standard deviation from its mean absolute value.
constexpr double kMeanAbsoluteToSd = 1.2533141373155003;  // sqrt(pi / 2)
// A normal error's standard deviation from its median absolute value.
constexpr double kMedianAbsoluteToSd = 1.4826;

double RelativeStd(double std, double value) {
  return std::isnan(std) ? 0.0 : std::abs(std / value);  // not given: nothing says it is wrong
}

// The interpolation's own relative error, as a standard deviation (NaN with < 2 branches).
double ModelRelativeError(const InterpolationModel& model) {
  return kMeanAbsoluteToSd * model.leave_one_out_log_error;
}

// The interpolation fitted without sample `leave`: its prediction for that branch and its error.
void PredictWithout(const Tree& tree, const std::vector<BranchSample>& samples, int leave,
                    const InterpolationOptions& options, SampleVerdict& verdict) {
  std::vector<BranchSample> others;
  for (int i = 0; i < static_cast<int>(samples.size()); ++i) {
    if (i != leave) others.push_back(samples[i]);
  }
  InterpolationOptions unclamped = options;
  unclamped.clamp_to_measured = false;  // the others' range need not hold this branch
  const InterpolationModel model = FitInterpolationModel(tree, others, unclamped);
  const BranchSample& s = samples[leave];
  verdict.predicted_hz = model.Frequency(tree, s.branch);
  const double distance = std::abs(std::log(s.frequency_hz / verdict.predicted_hz));
  const double own = RelativeStd(s.frequency_std_hz, s.frequency_hz);
  const double spread = std::hypot(own, ModelRelativeError(model));
  verdict.z = spread > 0 ? distance / spread : kNaN;
  verdict.effective_relative_error = std::max(own, distance);
}

// A relative sd over its bound, or infinite (the fit's covariance broke down: uncertain even when
// the bound is off); NaN (none given) is not.
bool OverBound(double relative, double bound) {
  return std::isinf(relative) || (!std::isnan(relative) && relative > bound);
}

// "frequency sd 31.2% of its value (over 10%)", or that none is known.
std::string DeviationReason(const char* what, double relative, double bound) {
  if (std::isinf(relative))
    return fmt::format("{} sd unknown (the fit's covariance broke down)", what);
  return fmt::format("{} sd {:.1f}% of its value (over {:.0f}%)", what, 100 * relative,
                     100 * bound);
}

}  // namespace

void UncertaintyOptions::Validate() const {
  // Each bound > 0; infinite turns its test off.
  const char* expected = "a value > 0 (infinite: off)";
  CheckThat(max_frequency_relative_std > 0, "max_frequency_relative_std", expected,
            max_frequency_relative_std);
  CheckThat(max_damping_relative_std > 0, "max_damping_relative_std", expected,
            max_damping_relative_std);
  CheckThat(max_z > 0, "max_z", expected, max_z);
}

std::vector<SampleVerdict> JudgeSamples(const Tree& tree, const std::vector<BranchSample>& samples,
                                        const UncertaintyOptions& options,
                                        const InterpolationOptions& interpolation) {
  std::vector<SampleVerdict> verdicts(samples.size());
  if (!options.flag) return verdicts;
  for (int i = 0; i < static_cast<int>(samples.size()); ++i) {
    const BranchSample& s = samples[i];
    SampleVerdict& v = verdicts[i];
    const double rel_f = s.frequency_std_hz / s.frequency_hz,
                 rel_z = s.damping_std / s.damping_ratio;
    v.predicted_hz = v.z = kNaN;
    v.effective_relative_error = RelativeStd(s.frequency_std_hz, s.frequency_hz);
    if (samples.size() >= 3) PredictWithout(tree, samples, i, interpolation, v);
    std::vector<std::string> reasons;
    if (OverBound(rel_f, options.max_frequency_relative_std)) {
      reasons.push_back(DeviationReason("frequency", rel_f, options.max_frequency_relative_std));
      v.frequency_flag = true;
    }
    if (OverBound(rel_z, options.max_damping_relative_std)) {
      reasons.push_back(DeviationReason("damping", rel_z, options.max_damping_relative_std));
      v.damping_flag = true;
    }
    if (v.z > options.max_z) {
      reasons.push_back(
          fmt::format("{:.3f} Hz is {:.1f} sd from the {:.3f} Hz the other branches "
                      "predict",
                      s.frequency_hz, v.z, v.predicted_hz));
      v.frequency_flag = true;
    }
    for (size_t r = 0; r < reasons.size(); ++r) v.why += (r ? "; " : "") + reasons[r];
  }
  return verdicts;
}

bool FrequencyIsLessCertain(const SampleVerdict& verdict, const InterpolationModel& model) {
  return verdict.frequency_flag && ModelRelativeError(model) < verdict.effective_relative_error;
}

bool DampingIsLessCertain(const SampleVerdict& verdict, const BranchSample& sample,
                          const std::vector<BranchSample>& trusted) {
  if (!verdict.damping_flag) return false;
  std::vector<double> log_z, deviation;
  for (const BranchSample& t : trusted) log_z.push_back(std::log(t.damping_ratio));
  const double centre = Median(log_z);
  for (double v : log_z) deviation.push_back(std::abs(v - centre));
  const double spread = kMedianAbsoluteToSd * Median(deviation);
  return spread < RelativeStd(sample.damping_std, sample.damping_ratio);
}

}  // namespace simtree::simready
