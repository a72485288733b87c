#include "simtree/identification/interpolation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <Eigen/QR>

#include "simtree/core/error.h"
#include "simtree/core/statistics.h"

namespace simtree {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Predictors of a branch for a model: (1), (1, log(r/L^2)) or (1, log r, log L).
Eigen::VectorXd Features(FrequencyModelKind kind, double radius, double length) {
  const double lr = std::log(std::max(radius, 1e-6));
  const double ll = std::log(std::max(length, 1e-6));
  switch (kind) {
    case FrequencyModelKind::kMedian:
      return Eigen::VectorXd::Ones(1);
    case FrequencyModelKind::kCantilever:
      return Eigen::Vector2d(1.0, lr - 2.0 * ll);
    case FrequencyModelKind::kLengthAndRadius:
      return Eigen::Vector3d(1.0, lr, ll);
  }
  return Eigen::VectorXd::Ones(1);
}

// Least-squares coefficients of log f on the features (the median of log f for kMedian, so one
// odd branch does not pull the constant).
std::vector<double> Fit(FrequencyModelKind kind, const std::vector<Eigen::VectorXd>& x,
                        const std::vector<double>& y) {
  if (kind == FrequencyModelKind::kMedian) return {Median(y)};
  const int n = static_cast<int>(y.size()), p = static_cast<int>(x.front().size());
  Eigen::MatrixXd a(n, p);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) {
    a.row(i) = x[i].transpose();
    b[i] = y[i];
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

}  // namespace

const char* ToString(FrequencyModelKind kind) {
  switch (kind) {
    case FrequencyModelKind::kMedian:
      return "median";
    case FrequencyModelKind::kCantilever:
      return "cantilever";
    case FrequencyModelKind::kLengthAndRadius:
      return "length_and_radius";
  }
  return "?";
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
    case FrequencyModelKind::kCantilever:
      formula = fmt::format("log f = {:.3f} + {:.3f} log(r/L^2)", coefficients[0], coefficients[1]);
      break;
    case FrequencyModelKind::kLengthAndRadius:
      formula = fmt::format("log f = {:.3f} + {:.3f} log r + {:.3f} log L", coefficients[0],
                            coefficients[1], coefficients[2]);
      break;
  }
  return fmt::format("{}, clamped to {:.3f}-{:.3f} Hz, leave-one-out {:.1f}%, {} measured branches",
                     formula, min_frequency_hz, max_frequency_hz,
                     100 * (std::exp(leave_one_out_log_rms) - 1), measured);
}

InterpolationModel FitInterpolationModel(const Tree& tree, const std::vector<BranchSample>& samples,
                                         const InterpolationOptions& options) {
  if (samples.empty()) {
    throw InputError("materials", "", "no measured branch to interpolate from");
  }
  InterpolationModel model;
  model.clamp = options.clamp_to_measured;
  model.measured = static_cast<int>(samples.size());
  std::vector<double> log_f, damping;
  std::vector<std::vector<double>> by_level(tree.MaxLevel() + 1);
  std::vector<std::pair<double, double>> geometry;
  model.min_frequency_hz = std::numeric_limits<double>::infinity();
  model.max_frequency_hz = 0;
  for (const BranchSample& s : samples) {
    if (s.branch < 0 || s.branch >= tree.size()) {
      throw InputError("materials", fmt::format("branch {}", s.branch),
                       fmt::format("not in the tree (it has {} branches)", tree.size()));
    }
    const Branch& b = tree.branches[s.branch];
    geometry.emplace_back(b.base().radius, b.Length());
    log_f.push_back(std::log(s.frequency_hz));
    damping.push_back(s.damping_ratio);
    by_level[b.level].push_back(s.damping_ratio);
    model.min_frequency_hz = std::min(model.min_frequency_hz, s.frequency_hz);
    model.max_frequency_hz = std::max(model.max_frequency_hz, s.frequency_hz);
  }
  model.median_damping = Median(damping);
  for (const auto& level : by_level) model.level_damping.push_back(Median(level));

  // Candidate models the data can carry; the one with the smallest leave-one-out error wins.
  const int n = static_cast<int>(samples.size());
  std::vector<FrequencyModelKind> kinds = {FrequencyModelKind::kMedian};
  auto features = [&](FrequencyModelKind kind) {
    std::vector<Eigen::VectorXd> x;
    for (const auto& [r, l] : geometry) x.push_back(Features(kind, r, l));
    return x;
  };
  if (n >= options.min_branches_cantilever &&
      Varies(features(FrequencyModelKind::kCantilever), 1)) {
    kinds.push_back(FrequencyModelKind::kCantilever);
  }
  if (n >= options.min_branches_two_slopes &&
      Varies(features(FrequencyModelKind::kLengthAndRadius), 1) &&
      Varies(features(FrequencyModelKind::kLengthAndRadius), 2)) {
    kinds.push_back(FrequencyModelKind::kLengthAndRadius);
  }
  double best_error = std::numeric_limits<double>::infinity();
  for (FrequencyModelKind kind : kinds) {
    const std::vector<Eigen::VectorXd> x = features(kind);
    double error = kNaN;
    if (n >= 2) {
      double sum = 0;
      for (int leave = 0; leave < n; ++leave) {
        std::vector<Eigen::VectorXd> xs;
        std::vector<double> ys;
        for (int i = 0; i < n; ++i) {
          if (i == leave) continue;
          xs.push_back(x[i]);
          ys.push_back(log_f[i]);
        }
        double predicted = Predict(Fit(kind, xs, ys), x[leave]);
        if (options.clamp_to_measured) {
          predicted = std::clamp(predicted, std::log(model.min_frequency_hz),
                                 std::log(model.max_frequency_hz));
        }
        sum += std::pow(predicted - log_f[leave], 2);
      }
      error = std::sqrt(sum / n);
    }
    // Ties (and n < 2) keep the simpler model.
    if (kind == FrequencyModelKind::kMedian || error < best_error - 1e-12) {
      best_error = std::isnan(error) ? std::numeric_limits<double>::infinity() : error;
      model.kind = kind;
      model.coefficients = Fit(kind, x, log_f);
      model.leave_one_out_log_rms = error;
    }
  }
  return model;
}

}  // namespace simtree
