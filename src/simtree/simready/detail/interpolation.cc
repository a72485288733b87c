#include "simtree/simready/detail/interpolation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <Eigen/QR>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/statistics.h"
#include "simtree/core/units.h"
#include "simtree/simready/detail/sample_weights.h"

namespace simtree::simready {
namespace {

// Predictors of a branch for a model: (1), (1, log(r/L^2)) or (1, log r, log L).
Eigen::VectorXd Features(FrequencyModelKind kind, double radius, double length) {
  const double lr = std::log(std::max(radius, 1e-6));
  const double ll = std::log(std::max(length, 1e-6));
  switch (kind) {
    case FrequencyModelKind::kMedian:
    case FrequencyModelKind::kNearestMeasuredAncestor:  // the median where no ancestor is measured
      return Eigen::VectorXd::Ones(1);
    case FrequencyModelKind::kCantilever:
      return Eigen::Vector2d(1.0, lr - 2.0 * ll);
    case FrequencyModelKind::kLengthAndRadius:
      return Eigen::Vector3d(1.0, lr, ll);
  }
  return Eigen::VectorXd::Ones(1);
}

// Weighted least-squares coefficients of log f on the features (the weighted median of log f for
// the one-constant models, so one odd branch does not pull the constant).
std::vector<double> Fit(const std::vector<Eigen::VectorXd>& x, const std::vector<double>& y,
                        const std::vector<double>& w) {
  if (x.front().size() == 1) return {WeightedMedian(y, w)};
  const int n = static_cast<int>(y.size()), p = static_cast<int>(x.front().size());
  Eigen::MatrixXd a(n, p);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    const double root_w = std::sqrt(w[i]);
    a.row(i) = root_w * x[i].transpose();
    b[i] = root_w * y[i];
  }
  const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
  return std::vector<double>(c.data(), c.data() + c.size());
}

double Predict(const std::vector<double>& c, const Eigen::VectorXd& x) {
  double s = 0;
  for (int i = 0; i < x.size(); ++i) s += c[i] * x[i];
  return s;
}

// Whether the predictors vary enough across the samples to fit slopes on them.
bool Varies(const std::vector<Eigen::VectorXd>& x, int column) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& v : x) {
    lo = std::min(lo, v[column]);
    hi = std::max(hi, v[column]);
  }
  return hi - lo > 0.05;  // 5% in log: anything less is one size
}

// The log frequency of the nearest ancestor of `branch` with a finite value in `log_f`, else
// `fallback`.
double AncestorLogFrequency(const Tree& tree, const std::vector<double>& log_f, int branch,
                            double fallback) {
  for (int a = tree.branches[branch].parent; a >= 0; a = tree.branches[a].parent) {
    if (std::isfinite(log_f[a])) return log_f[a];
  }
  return fallback;
}

}  // namespace

const char* ToString(FrequencyModelKind kind) {
  switch (kind) {
    case FrequencyModelKind::kMedian:
      return "median";
    case FrequencyModelKind::kNearestMeasuredAncestor:
      return "nearest_measured_ancestor";
    case FrequencyModelKind::kCantilever:
      return "cantilever";
    case FrequencyModelKind::kLengthAndRadius:
      return "length_and_radius";
  }
  return "?";
}

double InterpolationModel::Frequency(const Tree& tree, int branch) const {
  if (static_cast<int>(measured_frequency_hz.size()) != tree.size() || branch < 0 ||
      branch >= tree.size()) {
    throw InputError("interpolation", fmt::format("branch {}", branch),
                     fmt::format("not a branch of the tree the model was fitted on ({} branches)",
                                 measured_frequency_hz.size()));
  }
  const Branch& b = tree.branches[branch];
  if (kind != FrequencyModelKind::kNearestMeasuredAncestor) {
    return Frequency(b.base().radius, b.Length());
  }
  double f = std::exp(coefficients[0]);
  for (int a = b.parent; a >= 0; a = tree.branches[a].parent) {
    if (std::isfinite(measured_frequency_hz[a])) {
      f = measured_frequency_hz[a];
      break;
    }
  }
  return clamp ? std::clamp(f, min_frequency_hz, max_frequency_hz) : f;
}

double InterpolationModel::Frequency(double radius_m, double length_m) const {
  const double f = std::exp(Predict(coefficients, Features(kind, radius_m, length_m)));
  return clamp ? std::clamp(f, min_frequency_hz, max_frequency_hz) : f;
}

double InterpolationModel::Damping(int level) const {
  if (level >= 0 && level < static_cast<int>(level_damping.size()) &&
      std::isfinite(level_damping[level])) {
    return level_damping[level];
  }
  // The nearest measured level (the mean of the two when both sides are as near).
  for (int d = 1; d < static_cast<int>(level_damping.size()) + level + 1; ++d) {
    double sum = 0;
    int count = 0;
    for (int l : {level - d, level + d}) {
      if (l >= 0 && l < static_cast<int>(level_damping.size()) && std::isfinite(level_damping[l])) {
        sum += level_damping[l];
        ++count;
      }
    }
    if (count) return sum / count;
  }
  return median_damping;
}

std::string InterpolationModel::Describe() const {
  std::string formula;
  switch (kind) {
    case FrequencyModelKind::kMedian:
      formula = fmt::format("f = {:.3f} Hz (median)", std::exp(coefficients[0]));
      break;
    case FrequencyModelKind::kNearestMeasuredAncestor:
      formula = fmt::format(
          "f = the nearest measured ancestor's (the median, {:.3f} Hz, where none is measured)",
          std::exp(coefficients[0]));
      break;
    case FrequencyModelKind::kCantilever:
      formula = fmt::format("log f = {:.3f} + {:.3f} log(r/L^2)", coefficients[0], coefficients[1]);
      break;
    case FrequencyModelKind::kLengthAndRadius:
      formula = fmt::format("log f = {:.3f} + {:.3f} log r + {:.3f} log L", coefficients[0],
                            coefficients[1], coefficients[2]);
      break;
  }
  return fmt::format(
      "{}, clamped to {:.3f}-{:.3f} Hz, leave-one-out {:.1f}%, {} measured branches{}", formula,
      min_frequency_hz, max_frequency_hz, 100 * (std::exp(leave_one_out_log_error) - 1), measured,
      weighted ? ", weighted by 1/sd^2" : "");
}

void InterpolationOptions::Validate() const {
  CheckAtLeast("min_branches_cantilever", min_branches_cantilever, 3);
  CheckAtLeast("min_branches_two_slopes", min_branches_two_slopes, 4);
}

namespace {

// What the models are fitted on: per sample its branch's log frequency and geometry, and each
// branch's measured log frequency (the mean when several samples name it), with one sample left
// out on request for leave-one-out.
struct Measurements {
  const Tree& tree;
  const std::vector<BranchSample>& samples;
  std::vector<double> log_f;
  std::vector<double> weight_f, weight_z;           // per sample, 1 when unweighted
  std::vector<std::pair<double, double>> geometry;  // base radius, length
  std::vector<double> log_f_sum;                    // per branch
  std::vector<int> count;                           // per branch

  Measurements(const Tree& t, const std::vector<BranchSample>& s, bool weighted)
      : tree(t), samples(s) {
    log_f_sum.assign(tree.size(), 0.0);
    count.assign(tree.size(), 0);
    std::vector<double> f, z, f_std, z_std;
    for (const BranchSample& sample : samples) {
      const Branch& b = tree.branches[sample.branch];
      geometry.emplace_back(b.base().radius, b.Length());
      log_f.push_back(std::log(sample.frequency_hz));
      f.push_back(sample.frequency_hz);
      z.push_back(sample.damping_ratio);
      f_std.push_back(weighted ? sample.frequency_std_hz : kNaN);
      z_std.push_back(weighted ? sample.damping_std : kNaN);
    }
    weight_f = InverseVarianceWeights(f, f_std);
    weight_z = InverseVarianceWeights(z, z_std);
    for (size_t i = 0; i < samples.size(); ++i) {
      log_f_sum[samples[i].branch] += log_f[i];
      ++count[samples[i].branch];
    }
  }
  int size() const { return static_cast<int>(samples.size()); }

  // Each branch's log frequency (NaN where none is measured) with sample `leave` left out (-1:
  // none).
  std::vector<double> BranchLogFrequency(int leave) const {
    std::vector<double> out(tree.size(), kNaN);
    for (int b = 0; b < tree.size(); ++b) {
      const bool left = leave >= 0 && samples[leave].branch == b;
      const int c = count[b] - (left ? 1 : 0);
      if (c > 0) out[b] = (log_f_sum[b] - (left ? log_f[leave] : 0.0)) / c;
    }
    return out;
  }

  std::vector<Eigen::VectorXd> Predictors(FrequencyModelKind kind) const {
    std::vector<Eigen::VectorXd> x;
    for (const auto& [r, l] : geometry) x.push_back(Features(kind, r, l));
    return x;
  }
};

// The measured range, the damping per level, and each branch's measured frequency.
InterpolationModel MeasuredValues(const Measurements& data, const InterpolationOptions& options) {
  InterpolationModel model;
  model.clamp = options.clamp_to_measured;
  model.weighted = options.weight_by_uncertainty;
  model.measured = data.size();
  std::vector<double> damping;
  const int levels = data.tree.MaxLevel() + 1;
  std::vector<std::vector<double>> by_level(levels), level_weight(levels);
  model.min_frequency_hz = std::numeric_limits<double>::infinity();
  model.max_frequency_hz = 0;
  for (int i = 0; i < data.size(); ++i) {
    const BranchSample& s = data.samples[i];
    damping.push_back(s.damping_ratio);
    const int level = data.tree.branches[s.branch].level;
    by_level[level].push_back(s.damping_ratio);
    level_weight[level].push_back(data.weight_z[i]);
    model.min_frequency_hz = std::min(model.min_frequency_hz, s.frequency_hz);
    model.max_frequency_hz = std::max(model.max_frequency_hz, s.frequency_hz);
  }
  model.median_damping = WeightedMedian(damping, data.weight_z);
  for (int l = 0; l < levels; ++l) {
    model.level_damping.push_back(WeightedMedian(by_level[l], level_weight[l]));
  }
  model.measured_frequency_hz = data.BranchLogFrequency(-1);
  for (double& f : model.measured_frequency_hz) f = std::exp(f);  // NaN stays NaN
  return model;
}

// The models the data can carry, simplest first: slopes need enough branches that vary in size.
std::vector<FrequencyModelKind> CandidateModels(const Measurements& data,
                                                const InterpolationOptions& options) {
  std::vector<FrequencyModelKind> kinds = {FrequencyModelKind::kMedian,
                                           FrequencyModelKind::kNearestMeasuredAncestor};
  const int n = data.size();
  if (n >= options.min_branches_cantilever &&
      Varies(data.Predictors(FrequencyModelKind::kCantilever), 1)) {
    kinds.push_back(FrequencyModelKind::kCantilever);
  }
  if (n >= options.min_branches_two_slopes &&
      Varies(data.Predictors(FrequencyModelKind::kLengthAndRadius), 1) &&
      Varies(data.Predictors(FrequencyModelKind::kLengthAndRadius), 2)) {
    kinds.push_back(FrequencyModelKind::kLengthAndRadius);
  }
  return kinds;
}

// Mean absolute leave-one-out error of log f for model `kind`, weighted by the samples' frequency
// weights (NaN with fewer than 2 samples).
double LeaveOneOutError(FrequencyModelKind kind, const Measurements& data,
                        const InterpolationModel& model) {
  const int n = data.size();
  if (n < 2) return kNaN;
  const std::vector<Eigen::VectorXd> x = data.Predictors(kind);
  double sum = 0, weights = 0;
  for (int leave = 0; leave < n; ++leave) {
    std::vector<Eigen::VectorXd> xs;
    std::vector<double> ys, ws;
    for (int i = 0; i < n; ++i) {
      if (i == leave) continue;
      xs.push_back(x[i]);
      ys.push_back(data.log_f[i]);
      ws.push_back(data.weight_f[i]);
    }
    double predicted = Predict(Fit(xs, ys, ws), x[leave]);
    if (kind == FrequencyModelKind::kNearestMeasuredAncestor) {
      predicted = AncestorLogFrequency(data.tree, data.BranchLogFrequency(leave),
                                       data.samples[leave].branch, predicted);
    }
    if (model.clamp) {
      predicted =
          std::clamp(predicted, std::log(model.min_frequency_hz), std::log(model.max_frequency_hz));
    }
    sum += data.weight_f[leave] * std::abs(predicted - data.log_f[leave]);
    weights += data.weight_f[leave];
  }
  return sum / weights;
}

}  // namespace

InterpolationModel FitInterpolationModel(const Tree& tree, const std::vector<BranchSample>& samples,
                                         const InterpolationOptions& options) {
  options.Validate();
  if (samples.empty()) {
    throw InputError("materials", "", "no measured branch to interpolate from");
  }
  for (const BranchSample& s : samples) {
    if (s.branch < 0 || s.branch >= tree.size()) {
      throw InputError("materials", fmt::format("branch {}", s.branch),
                       fmt::format("not in the tree (it has {} branches)", tree.size()));
    }
  }
  const Measurements data(tree, samples, options.weight_by_uncertainty);
  InterpolationModel model = MeasuredValues(data, options);
  // The candidate with the smallest leave-one-out error wins; ties (and n < 2) keep the simpler
  // model, the earlier in the list.
  double best_error = std::numeric_limits<double>::infinity();
  for (FrequencyModelKind kind : CandidateModels(data, options)) {
    const double error = LeaveOneOutError(kind, data, model);
    if (kind == FrequencyModelKind::kMedian || error < best_error - 1e-12) {
      best_error = std::isnan(error) ? std::numeric_limits<double>::infinity() : error;
      model.kind = kind;
      model.coefficients = Fit(data.Predictors(kind), data.log_f, data.weight_f);
      model.leave_one_out_log_error = error;
    }
  }
  return model;
}

}  // namespace simtree::simready
