#include "simtree/identification/detail/joint_poles.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <Eigen/SVD>

#include "simtree/core/option_checks.h"
#include "simtree/core/units.h"

namespace simtree::identification {
namespace {

// The indices of a record's valid samples.
std::vector<int> ValidRows(const SampledSignal& signal) {
  std::vector<int> rows;
  for (int i = 0; i < signal.size(); ++i) {
    if (signal.valid[i]) rows.push_back(i);
  }
  return rows;
}

// One link's reading of the joint poles: offsets and residual from linear least squares on all
// poles over its valid samples (t from the start of the shared grid), each mode's amplitudes from
// that mode alone.
DampedSinusoidFit FitAmplitudes(const SampledSignal& signal, const DampedSinusoidFit& joint) {
  const int modes = static_cast<int>(joint.modes.size());
  const int channels = signal.channels();
  const std::vector<int> rows = ValidRows(signal);
  const int n = static_cast<int>(rows.size());
  Eigen::MatrixXd x(n, 1 + 2 * modes), y(n, channels);
  for (int j = 0; j < n; ++j) {
    const double t = rows[j] * signal.dt;
    x(j, 0) = 1.0;
    for (int k = 0; k < modes; ++k) {
      const FittedMode& m = joint.modes[k];
      const double e = std::exp(-m.decay_rate * t);
      x(j, 1 + 2 * k) = e * std::cos(m.angular_frequency * t);
      x(j, 2 + 2 * k) = e * std::sin(m.angular_frequency * t);
    }
    y.row(j) = signal.values.row(rows[j]);
  }
  const Eigen::MatrixXd coef = x.colPivHouseholderQr().solve(y);
  DampedSinusoidFit out;
  out.converged = joint.converged;
  out.message = joint.message;
  out.iterations = joint.iterations;
  out.candidates = joint.candidates;
  out.residual_correlation = joint.residual_correlation;
  out.offsets = coef.row(0).transpose();
  out.rms_residual = n > 0 ? std::sqrt((y - x * coef).squaredNorm() / (n * channels)) : 0.0;
  for (int k = 0; k < modes; ++k) {
    FittedMode mode = joint.modes[k];
    // The mode's amplitudes alone (with the offset): in the joint least squares two close poles
    // can take large amplitudes of opposite sign that cancel, and a broad pole beside a narrow one
    // would then look strongest. Alone, each reads what a matched filter at its pole reads.
    Eigen::MatrixXd alone(n, 3);
    alone << x.col(0), x.col(1 + 2 * k), x.col(2 + 2 * k);
    const Eigen::MatrixXd own = alone.colPivHouseholderQr().solve(y);
    mode.cos_amplitude = own.row(1).transpose();
    mode.sin_amplitude = own.row(2).transpose();
    mode.channel_amplitude.resize(channels);
    for (int c = 0; c < channels; ++c) {
      mode.channel_amplitude[c] = std::hypot(mode.cos_amplitude[c], mode.sin_amplitude[c]);
    }
    mode.amplitude = mode.channel_amplitude.norm();
    out.modes.push_back(std::move(mode));
  }
  std::stable_sort(
      out.modes.begin(), out.modes.end(),
      [](const FittedMode& a, const FittedMode& b) { return a.amplitude > b.amplitude; });
  return out;
}

// Every link's valid samples, scaled like the stacked record.
struct LinkSamples {
  std::vector<double> t;
  Eigen::MatrixXd y;
};

// The residual of every link, stacked, for poles (s_k, w_k) = (p[2k], p[2k + 1]) with each link's
// offsets and amplitudes by linear least squares (variable projection).
Eigen::VectorXd ProjectedResidual(const std::vector<LinkSamples>& links, const Eigen::VectorXd& p) {
  const int modes = static_cast<int>(p.size() / 2);
  Eigen::Index total = 0;
  for (const LinkSamples& l : links) total += l.y.size();
  Eigen::VectorXd out(total);
  Eigen::Index at = 0;
  for (const LinkSamples& l : links) {
    const int n = static_cast<int>(l.t.size());
    Eigen::MatrixXd x(n, 1 + 2 * modes);
    for (int j = 0; j < n; ++j) {
      x(j, 0) = 1.0;
      for (int k = 0; k < modes; ++k) {
        const double e = std::exp(-p[2 * k] * l.t[j]);
        x(j, 1 + 2 * k) = e * std::cos(p[2 * k + 1] * l.t[j]);
        x(j, 2 + 2 * k) = e * std::sin(p[2 * k + 1] * l.t[j]);
      }
    }
    const Eigen::MatrixXd r = l.y - x * x.colPivHouseholderQr().solve(l.y);
    out.segment(at, r.size()) = Eigen::Map<const Eigen::VectorXd>(r.data(), r.size());
    at += r.size();
  }
  return out;
}

// What a refinement leaves: the stacked residual's sum of squares, its length, and its lag-1
// autocorrelation (clamped to [0, 0.95]).
struct Refinement {
  double rss = 0.0;
  Eigen::Index count = 0;
  double lag1 = 0.0;
};

// Refines the poles of `fit` on every link's valid samples (no filled gaps, no components left
// out): Levenberg-Marquardt on the poles alone, forward-difference Jacobian; the poles' standard
// errors from that Jacobian (the amplitudes projected out), inflated for lag-1 correlated
// residuals as FitDampedSinusoids does.
Refinement RefinePoles(const std::vector<LinkSamples>& links, int linear_parameters,
                       DampedSinusoidFit& fit) {
  const int modes = static_cast<int>(fit.modes.size());
  Eigen::VectorXd p(2 * modes);
  for (int k = 0; k < modes; ++k) {
    p[2 * k] = fit.modes[k].decay_rate;
    p[2 * k + 1] = fit.modes[k].angular_frequency;
  }
  auto jacobian = [&](const Eigen::VectorXd& at, const Eigen::VectorXd& r0) {
    Eigen::MatrixXd j(r0.size(), at.size());
    for (int i = 0; i < at.size(); ++i) {
      Eigen::VectorXd q = at;
      const double h = 1e-6 * std::max(1.0, std::abs(at[i]));
      q[i] += h;
      j.col(i) = (ProjectedResidual(links, q) - r0) / h;
    }
    return j;
  };
  Eigen::VectorXd r = ProjectedResidual(links, p);
  double rss = r.squaredNorm(), lambda = 1e-3;
  bool converged = false;
  for (int it = 0; it < 100 && !converged; ++it) {
    const Eigen::MatrixXd j = jacobian(p, r);
    const Eigen::MatrixXd jtj = j.transpose() * j;
    const Eigen::VectorXd jtr = j.transpose() * r;
    bool improved = false;
    for (int attempt = 0; attempt < 12 && !improved; ++attempt) {
      Eigen::MatrixXd a = jtj;
      for (int i = 0; i < a.rows(); ++i) a(i, i) += lambda * std::max(jtj(i, i), 1e-12);
      const Eigen::VectorXd trial = p - a.ldlt().solve(jtr);
      const Eigen::VectorXd trial_r = ProjectedResidual(links, trial);
      const double trial_rss = trial_r.squaredNorm();
      if (std::isfinite(trial_rss) && trial_rss < rss) {
        const double gain = (rss - trial_rss) / std::max(rss, 1e-300);
        p = trial;
        r = trial_r;
        rss = trial_rss;
        lambda = std::max(lambda / 3.0, 1e-12);
        improved = true;
        converged = gain < 1e-10;
      } else {
        lambda *= 4.0;
      }
    }
    converged = converged || !improved;  // no step lowers the residual: a minimum
  }
  // Covariance of the poles.
  const Eigen::MatrixXd j = jacobian(p, r);
  const double dof = std::max<double>(1.0, r.size() - p.size() - linear_parameters);
  double lag0 = r.squaredNorm(), lag1 = 0;
  for (Eigen::Index i = 0; i + 1 < r.size(); ++i) lag1 += r[i] * r[i + 1];
  const double rho = lag0 > 0 ? std::clamp(lag1 / lag0, 0.0, 0.95) : 0.0;
  const Eigen::MatrixXd cov =
      (j.transpose() * j).completeOrthogonalDecomposition().pseudoInverse() * (rss / dof) *
      (1 + rho) / (1 - rho);
  for (int k = 0; k < modes; ++k) {
    SetPole(p[2 * k], std::abs(p[2 * k + 1]), cov.block<2, 2>(2 * k, 2 * k), fit.modes[k]);
  }
  return {rss, r.size(), rho};
}

// Parameters of a joint model of `modes` poles: two per pole, and per link channel an offset and
// two amplitudes per pole.
int JointParameters(int modes, int link_channels) {
  return 2 * modes + link_channels * (1 + 2 * modes);
}

// BIC of a joint model on the stacked residual. Its samples are not independent (unmodelled
// higher modes and a tracker's error leave the residual correlated from sample to sample), so
// they count as n (1 - rho) / (1 + rho) independent ones, the variance-equivalent count of an
// AR(1) series; with all n counted, every extra pole would look worth its parameters.
double JointBic(const Refinement& r, int parameters) {
  const double n = static_cast<double>(r.count);
  const double effective = std::max(2.0, n * (1.0 - r.lag1) / (1.0 + r.lag1));
  return effective * std::log(std::max(r.rss, 1e-300) / n) + parameters * std::log(effective);
}

// Close poles merged: BIC on the principal components may explain two modes a few percent apart
// by one pole whose damping takes up their beat. Every pole is offered split in two, a quarter of
// the record's frequency resolution (1 / T) either side, all poles refined on every link; the
// split that lowers the joint BIC most is kept, and the offers repeat until none does or the
// model holds `max_modes`. A split whose poles come back within `min_split` of each other (relative
// frequency) found no second mode and is not kept.
void SplitMergedPoles(const std::vector<LinkSamples>& links, int link_channels, double record_s,
                      const JointPolesOptions& options, Refinement& current,
                      DampedSinusoidFit& fit) {
  const double shift = kTwoPi * 0.25 / record_s;  // rad/s either side of the pole
  double current_bic =
      JointBic(current, JointParameters(static_cast<int>(fit.modes.size()), link_channels));
  while (static_cast<int>(fit.modes.size()) < options.max_modes) {
    const int modes = static_cast<int>(fit.modes.size());
    double best_bic = current_bic;
    DampedSinusoidFit best_fit;
    Refinement best_refinement;
    for (int k = 0; k < modes; ++k) {
      DampedSinusoidFit trial = fit;
      FittedMode upper = trial.modes[k];
      trial.modes[k].angular_frequency -= shift;
      upper.angular_frequency += shift;
      if (trial.modes[k].angular_frequency <= 0) continue;
      trial.modes.push_back(upper);
      const Refinement refined = RefinePoles(links, link_channels * (1 + 2 * (modes + 1)), trial);
      const double f_low = trial.modes[k].frequency_hz, f_high = trial.modes.back().frequency_hz;
      if (std::abs(f_high - f_low) < options.min_split * 0.5 * (f_high + f_low)) continue;
      const double bic = JointBic(refined, JointParameters(modes + 1, link_channels));
      if (bic < best_bic) {
        best_bic = bic;
        best_fit = std::move(trial);
        best_refinement = refined;
      }
    }
    if (!(best_bic < current_bic)) return;
    fit = std::move(best_fit);
    current = best_refinement;
    current_bic = best_bic;
  }
}

// The links' records stacked side by side, each gaps filled, mean removed and scaled to unit RMS
// (every link weighs the same), reduced to their strongest principal components.
struct Components {
  SampledSignal components;    // one channel per component, every sample valid
  std::vector<double> scales;  // per link: 1 / its RMS
  int channels = 0;            // of every link together
};

Components StackedComponents(const std::vector<SampledSignal>& signals,
                             const JointPolesOptions& options) {
  Components out;
  const SampledSignal& first = signals.front();
  for (const SampledSignal& s : signals) {
    if (s.size() != first.size() || s.dt != first.dt || s.start_time_s != first.start_time_s) {
      throw std::invalid_argument("joint poles: the links' records are not on the same grid");
    }
    out.channels += s.channels();
  }
  Eigen::MatrixXd stacked(first.size(), out.channels);
  int column = 0;
  for (const SampledSignal& s : signals) {
    Eigen::MatrixXd x = s.FilledValues();
    x.rowwise() -= x.colwise().mean();
    const double rms = std::sqrt(x.squaredNorm() / std::max<Eigen::Index>(1, x.size()));
    out.scales.push_back(rms > 0 ? 1.0 / rms : 1.0);
    x *= out.scales.back();
    stacked.middleCols(column, s.channels()) = x;
    column += s.channels();
  }
  Eigen::BDCSVD<Eigen::MatrixXd> svd(stacked, Eigen::ComputeThinU);
  const int components =
      std::min<int>(options.components, static_cast<int>(svd.singularValues().size()));
  SampledSignal& pcs = out.components;
  pcs.start_time_s = first.start_time_s;
  pcs.dt = first.dt;
  pcs.values =
      svd.matrixU().leftCols(components) * svd.singularValues().head(components).asDiagonal();
  pcs.valid.assign(first.size(), true);
  for (int c = 0; c < components; ++c) pcs.channel_names.push_back(fmt::format("pc{}", c + 1));
  return out;
}

// Every link's valid samples, scaled like the stack.
std::vector<LinkSamples> ScaledValidSamples(const std::vector<SampledSignal>& signals,
                                            const std::vector<double>& scales) {
  std::vector<LinkSamples> samples;
  for (size_t i = 0; i < signals.size(); ++i) {
    const SampledSignal& s = signals[i];
    LinkSamples l;
    const std::vector<int> rows = ValidRows(s);
    l.y.resize(static_cast<int>(rows.size()), s.channels());
    for (size_t j = 0; j < rows.size(); ++j) {
      l.t.push_back(rows[j] * s.dt);
      l.y.row(j) = s.values.row(rows[j]) * scales[i];
    }
    samples.push_back(std::move(l));
  }
  return samples;
}

}  // namespace

void JointPolesOptions::Validate() const {
  CheckAtLeast("components", components, 1);
  CheckAtLeast("max_modes", max_modes, 1);
  CheckThat(min_split >= 0 && min_split < 1, "min_split", "a relative frequency in [0, 1)",
            min_split);
}

JointPoles EstimateJointPoles(const std::vector<SampledSignal>& signals,
                              const EstimatorOptions& estimation,
                              const JointPolesOptions& options) {
  estimation.Validate();
  options.Validate();
  JointPoles out;
  if (signals.empty()) {
    out.message = "no link to fit joint poles to";
    return out;
  }
  // How many modes and where to start: estimator (c) on the links' principal components.
  const Components stack = StackedComponents(signals, options);
  const SampledSignal& pcs = stack.components;
  const double record_s = pcs.duration_s();
  const auto [min_hz, max_hz] = BandOf(estimation, record_s, pcs.dt);
  EstimatorOptions fit_options = estimation;
  fit_options.max_modes = options.max_modes;
  out.fit = FitDampedSinusoids(pcs, min_hz, max_hz, fit_options);
  if (out.fit.modes.empty()) {
    out.message = "joint poles: " + out.fit.message;
    return out;
  }
  // The poles refined on every link's own valid samples, merged poles split.
  const std::vector<LinkSamples> samples = ScaledValidSamples(signals, stack.scales);
  const int modes = static_cast<int>(out.fit.modes.size());
  Refinement refined = RefinePoles(samples, stack.channels * (1 + 2 * modes), out.fit);
  if (options.split_merged_poles) {
    SplitMergedPoles(samples, stack.channels, record_s, options, refined, out.fit);
    out.splits = static_cast<int>(out.fit.modes.size()) - modes;
  }
  out.ok = true;
  out.message =
      fmt::format("joint poles of {} links: {} modes on {} principal components{}", signals.size(),
                  out.fit.modes.size(), pcs.channels(),
                  out.splits > 0 ? fmt::format(", {} split on every link", out.splits) : "");
  // Each link reads the joint poles with its own amplitudes.
  for (const SampledSignal& s : signals) {
    SignalEstimate e;
    e.estimator = EstimatorKind::kDampedSinusoidFit;
    e.joint_poles = true;
    e.duration_s = record_s;
    e.noise_level = EstimateNoiseLevel(s).maxCoeff();
    DampedSinusoidFit amplitudes = FitAmplitudes(s, out.fit);
    MarkModesBeyondRecord(s, amplitudes);
    ReadFittedModes(std::move(amplitudes), s.channels(), record_s, min_hz, max_hz, estimation, e);
    out.links.push_back(std::move(e));
  }
  return out;
}

}  // namespace simtree::identification
