// Estimator (c): a constant plus damped sinusoids fitted to the whole free decay.
//
// Start: the matrix pencil method (Y. Hua and T. K. Sarkar, "Matrix pencil method for estimating
// parameters of exponentially damped/undamped sinusoids in noise", IEEE Trans. ASSP 38(5), 1990),
// with the Hankel matrices of all channels stacked so the channels share their poles. Refinement:
// Levenberg-Marquardt on the valid samples only, so gaps need no filling. The number of modes K is
// chosen by the Bayesian information criterion; the standard errors come from the Jacobian at the
// solution, inflated by (1 + rho) / (1 - rho) for residuals with lag-1 autocorrelation rho (the
// effective sample size of an AR(1) residual).

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>

#include "simtree/core/units.h"
#include "simtree/identification/estimators.h"

namespace simtree::identification {
namespace {

struct Pole {
  double decay_rate = 0.0;  // s, 1/s
  double omega = 0.0;       // damped angular frequency, rad/s
  double amplitude = 0.0;   // for ranking
};

double NaturalHz(double s, double w) { return std::hypot(s, w) / kTwoPi; }
double DampingRatio(double s, double w) { return s / std::hypot(s, w); }

// Poles of the filled, mean-removed record `x` (samples x channels) by the matrix pencil method.
std::vector<std::complex<double>> MatrixPencilPoles(const Eigen::MatrixXd& x, int max_order) {
  const int n = static_cast<int>(x.rows());
  const int channels = static_cast<int>(x.cols());
  const int pencil = std::clamp(n / 3, 2, 200);  // L: N/3 is the usual noise-robust choice
  const int rows = n - pencil;
  if (rows < 2) return {};
  Eigen::MatrixXd hankel(rows * channels, pencil + 1);
  for (int c = 0; c < channels; ++c) {
    for (int i = 0; i < rows; ++i) hankel.row(c * rows + i) = x.col(c).segment(i, pencil + 1);
  }
  Eigen::BDCSVD<Eigen::MatrixXd> svd(hankel, Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  // Singular values of noise alone stay within ~1.5x of their median for these shapes; count what
  // stands above twice the median as signal, and keep at least a few poles for BIC to choose from.
  std::vector<double> sorted(s.data(), s.data() + s.size());
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double floor = sorted[sorted.size() / 2];
  int order = 0;
  while (order < s.size() && s[order] > 2.0 * floor) ++order;
  order = std::clamp(std::max(order, max_order), 1, std::min<int>(max_order, pencil - 1));
  const Eigen::MatrixXd v = svd.matrixV().leftCols(order);
  const Eigen::MatrixXd v1 = v.topRows(pencil);
  const Eigen::MatrixXd v2 = v.bottomRows(pencil);
  const Eigen::MatrixXd a = v1.completeOrthogonalDecomposition().pseudoInverse() * v2;
  Eigen::EigenSolver<Eigen::MatrixXd> eig(a, false);
  std::vector<std::complex<double>> poles;
  for (int i = 0; i < eig.eigenvalues().size(); ++i) poles.push_back(eig.eigenvalues()[i]);
  return poles;
}

// The model's parameters: per mode (s, w); per channel an offset and (a, b) per mode.
struct Model {
  int modes = 0;
  int channels = 0;
  Eigen::VectorXd p;

  int size() const { return 2 * modes + channels * (1 + 2 * modes); }
  double& s(int k) { return p[2 * k]; }
  double& w(int k) { return p[2 * k + 1]; }
  int offset_index(int c) const { return 2 * modes + c * (1 + 2 * modes); }
  int a_index(int c, int k) const { return offset_index(c) + 1 + 2 * k; }
};

struct Samples {
  std::vector<double> t;   // valid samples' times from the record start
  Eigen::MatrixXd y;       // valid samples x channels
  std::vector<int> index;  // sample index of each valid sample
};

// Model values (valid samples x channels) and, when `jacobian` is set, d model / d p with rows
// ordered channel-major (all samples of channel 0 first).
Eigen::MatrixXd EvaluateModel(const Model& m, const std::vector<double>& t,
                              Eigen::MatrixXd* jacobian) {
  const int n = static_cast<int>(t.size());
  Eigen::MatrixXd out(n, m.channels);
  if (jacobian) jacobian->setZero(n * m.channels, m.size());
  for (int c = 0; c < m.channels; ++c) out.col(c).setConstant(m.p[m.offset_index(c)]);
  for (int k = 0; k < m.modes; ++k) {
    const double s = m.p[2 * k], w = m.p[2 * k + 1];
    for (int i = 0; i < n; ++i) {
      const double e = std::exp(-s * t[i]);
      const double cs = e * std::cos(w * t[i]);
      const double sn = e * std::sin(w * t[i]);
      for (int c = 0; c < m.channels; ++c) {
        const double a = m.p[m.a_index(c, k)], b = m.p[m.a_index(c, k) + 1];
        out(i, c) += a * cs + b * sn;
        if (jacobian) {
          const int row = c * n + i;
          (*jacobian)(row, 2 * k) += -t[i] * (a * cs + b * sn);
          (*jacobian)(row, 2 * k + 1) += t[i] * (-a * sn + b * cs);
          (*jacobian)(row, m.a_index(c, k)) = cs;
          (*jacobian)(row, m.a_index(c, k) + 1) = sn;
        }
      }
    }
  }
  if (jacobian) {
    for (int c = 0; c < m.channels; ++c) {
      for (int i = 0; i < n; ++i) (*jacobian)(c * n + i, m.offset_index(c)) = 1.0;
    }
  }
  return out;
}

// Offsets and amplitudes by linear least squares for fixed poles.
void SolveLinear(Model& m, const Samples& data) {
  const int n = static_cast<int>(data.t.size());
  Eigen::MatrixXd x(n, 1 + 2 * m.modes);
  for (int i = 0; i < n; ++i) {
    x(i, 0) = 1.0;
    for (int k = 0; k < m.modes; ++k) {
      const double e = std::exp(-m.p[2 * k] * data.t[i]);
      x(i, 1 + 2 * k) = e * std::cos(m.p[2 * k + 1] * data.t[i]);
      x(i, 2 + 2 * k) = e * std::sin(m.p[2 * k + 1] * data.t[i]);
    }
  }
  const Eigen::MatrixXd coef = x.colPivHouseholderQr().solve(data.y);
  for (int c = 0; c < m.channels; ++c) {
    m.p[m.offset_index(c)] = coef(0, c);
    for (int k = 0; k < m.modes; ++k) {
      m.p[m.a_index(c, k)] = coef(1 + 2 * k, c);
      m.p[m.a_index(c, k) + 1] = coef(2 + 2 * k, c);
    }
  }
}

double SumOfSquares(const Model& m, const Samples& data) {
  return (data.y - EvaluateModel(m, data.t, nullptr)).squaredNorm();
}

// J^T J of EvaluateModel's Jacobian. A channel's offset and amplitudes touch only its own rows,
// so J^T J is zero between channels: only the pole block, each channel's block and their coupling
// are formed, a channels-fold less work than the dense product.
Eigen::MatrixXd NormalMatrix(const Model& m, const Eigen::MatrixXd& jac) {
  const int n = static_cast<int>(jac.rows()) / std::max(m.channels, 1);
  const int poles = 2 * m.modes, width = 1 + 2 * m.modes;
  Eigen::MatrixXd jtj = Eigen::MatrixXd::Zero(m.size(), m.size());
  const auto pole_columns = jac.leftCols(poles);
  jtj.topLeftCorner(poles, poles).noalias() = pole_columns.transpose() * pole_columns;
  for (int c = 0; c < m.channels; ++c) {
    const int first = m.offset_index(c);
    const auto own = jac.block(c * n, first, n, width);
    jtj.block(first, first, width, width).noalias() = own.transpose() * own;
    jtj.block(0, first, poles, width).noalias() = jac.block(c * n, 0, n, poles).transpose() * own;
    jtj.block(first, 0, width, poles) = jtj.block(0, first, poles, width).transpose();
  }
  return jtj;
}

struct LmResult {
  Model model;
  double rss = 0.0;
  int iterations = 0;
  bool converged = false;
};

// Levenberg-Marquardt with Marquardt's diagonal scaling.
LmResult LevenbergMarquardt(Model m, const Samples& data, int max_iterations) {
  const int n = static_cast<int>(data.t.size());
  Eigen::MatrixXd jac;
  double rss = SumOfSquares(m, data);
  double lambda = 1e-3;
  LmResult out;
  for (int it = 0; it < max_iterations; ++it) {
    out.iterations = it + 1;
    const Eigen::MatrixXd model = EvaluateModel(m, data.t, &jac);
    Eigen::VectorXd r(n * m.channels);
    for (int c = 0; c < m.channels; ++c) r.segment(c * n, n) = data.y.col(c) - model.col(c);
    const Eigen::MatrixXd jtj = NormalMatrix(m, jac);
    const Eigen::VectorXd jtr = jac.transpose() * r;
    bool improved = false;
    for (int attempt = 0; attempt < 12 && !improved; ++attempt) {
      Eigen::MatrixXd a = jtj;
      for (int i = 0; i < a.rows(); ++i) a(i, i) += lambda * std::max(jtj(i, i), 1e-12);
      const Eigen::VectorXd step = a.ldlt().solve(jtr);
      Model trial = m;
      trial.p += step;
      const double trial_rss = SumOfSquares(trial, data);
      if (std::isfinite(trial_rss) && trial_rss < rss) {
        const double gain = (rss - trial_rss) / std::max(rss, 1e-300);
        m = trial;
        rss = trial_rss;
        lambda = std::max(lambda / 3.0, 1e-12);
        improved = true;
        if (gain < 1e-10) {
          out.converged = true;
          out.model = m;
          out.rss = rss;
          return out;
        }
      } else {
        lambda *= 4.0;
      }
    }
    if (!improved) {
      // No step lowers the residual: a minimum to the precision of the arithmetic.
      out.converged = true;
      break;
    }
  }
  out.model = m;
  out.rss = rss;
  return out;
}

// The valid samples of `signal`.
Samples ValidSamples(const SampledSignal& signal) {
  Samples data;
  for (int i = 0; i < signal.size(); ++i) {
    if (!signal.valid[i]) continue;
    data.t.push_back(i * signal.dt);
    data.index.push_back(i);
  }
  data.y.resize(static_cast<int>(data.t.size()), signal.channels());
  for (size_t j = 0; j < data.index.size(); ++j) data.y.row(j) = signal.values.row(data.index[j]);
  return data;
}

// Bayesian information criterion of a model with `parameters` parameters and residual sum of
// squares `rss` over `residuals` residuals.
double Bic(double rss, int parameters, int residuals) {
  return residuals * std::log(std::max(rss, 1e-300) / residuals) +
         parameters * std::log(static_cast<double>(residuals));
}

// The matrix pencil's poles of a record inside the band, as candidates for the model.
struct PoleFinder {
  double dt = 0.0;
  double min_hz = 0.0, max_hz = 0.0;
  const EstimatorOptions& options;

  // `x`: samples x channels, every sample filled, mean removed.
  std::vector<Pole> Find(const Eigen::MatrixXd& x) const {
    std::vector<Pole> poles;
    for (const std::complex<double>& z : MatrixPencilPoles(x, 2 * options.max_modes + 8)) {
      if (z.imag() <= 0 || std::abs(z) <= 0) continue;
      const double s = -std::log(std::abs(z)) / dt;
      const double w = std::arg(z) / dt;
      const double f = NaturalHz(s, w), zeta = DampingRatio(s, w);
      // Slightly growing poles are kept: noise can push a light mode across the unit circle, and
      // the refinement pulls it back.
      if (f < min_hz || f > max_hz || zeta > options.max_damping_ratio || zeta < -0.02) continue;
      poles.push_back({s, w, 0.0});
    }
    return poles;
  }
};

// What `model` leaves of the record on every sample (zero where the record has a gap).
Eigen::MatrixXd Residual(const Model& model, const Samples& data, int samples) {
  const Eigen::MatrixXd fitted = EvaluateModel(model, data.t, nullptr);
  Eigen::MatrixXd residual = Eigen::MatrixXd::Zero(samples, model.channels);
  for (size_t j = 0; j < data.index.size(); ++j) {
    residual.row(data.index[j]) = data.y.row(j) - fitted.row(j);
  }
  return residual;
}

// `offers` ranked by how much of `residual` each explains alone (strongest first).
std::vector<Pole> RankOffers(std::vector<Pole> offers, const Eigen::MatrixXd& residual,
                             const Samples& data) {
  const int n = static_cast<int>(data.t.size());
  for (Pole& pole : offers) {
    Eigen::MatrixXd x(n, 2);
    for (int j = 0; j < n; ++j) {
      const double e = std::exp(-pole.decay_rate * data.t[j]);
      x(j, 0) = e * std::cos(pole.omega * data.t[j]);
      x(j, 1) = e * std::sin(pole.omega * data.t[j]);
    }
    Eigen::MatrixXd r(n, residual.cols());
    for (int j = 0; j < n; ++j) r.row(j) = residual.row(data.index[j]);
    const Eigen::MatrixXd coef = x.colPivHouseholderQr().solve(r);
    pole.amplitude = (x * coef).norm();
  }
  std::stable_sort(offers.begin(), offers.end(),
                   [](const Pole& a, const Pole& b) { return a.amplitude > b.amplitude; });
  return offers;
}

// `base` with `pole` added, everything refitted.
LmResult FitWithPole(const Model& base, const Pole& pole, const Samples& data,
                     const EstimatorOptions& options) {
  Model m{base.modes + 1, base.channels, {}};
  m.p = Eigen::VectorXd::Zero(m.size());
  for (int k = 0; k < base.modes; ++k) {
    m.s(k) = base.p[2 * k];
    m.w(k) = base.p[2 * k + 1];
  }
  m.s(base.modes) = pole.decay_rate;
  m.w(base.modes) = pole.omega;
  SolveLinear(m, data);
  return LevenbergMarquardt(m, data, options.max_iterations);
}

// Forward selection: start from the offsets alone; at each step offer the strongest poles the
// matrix pencil finds in the current residual (and in the record), keep the addition that lowers
// the BIC most, refit everything, and stop when no addition lowers it. Working on the residual
// lets a second pole emerge beside a strong one that first absorbed a close pair.
LmResult SelectModes(const Samples& data, int samples, const PoleFinder& finder,
                     const std::vector<Pole>& record_poles, const EstimatorOptions& options) {
  const int channels = static_cast<int>(data.y.cols());
  const int residual_count = static_cast<int>(data.t.size()) * channels;
  LmResult best;
  best.model = Model{0, channels, Eigen::VectorXd::Zero(channels)};
  SolveLinear(best.model, data);
  best.rss = SumOfSquares(best.model, data);
  best.converged = true;
  double best_bic = Bic(best.rss, best.model.size(), residual_count);
  constexpr int kTrialsPerStep = 3;
  for (int step = 0; step < options.max_modes; ++step) {
    if (residual_count <= Model{step + 1, channels, {}}.size() + 2) break;
    const Eigen::MatrixXd residual = Residual(best.model, data, samples);
    std::vector<Pole> offers = finder.Find(residual);
    offers.insert(offers.end(), record_poles.begin(), record_poles.end());
    offers = RankOffers(std::move(offers), residual, data);
    LmResult step_best;
    double step_bic = std::numeric_limits<double>::infinity();
    for (int trial = 0; trial < std::min<int>(kTrialsPerStep, offers.size()); ++trial) {
      LmResult fit = FitWithPole(best.model, offers[trial], data, options);
      const double bic = Bic(fit.rss, fit.model.size(), residual_count);
      if (bic < step_bic) {
        step_bic = bic;
        step_best = std::move(fit);
      }
    }
    if (!(step_bic < best_bic)) break;
    best_bic = step_bic;
    best = std::move(step_best);
  }
  return best;
}

// A sampled sinusoid at w and at 2 pi / dt - w (or w + 2 pi k / dt) gives the same samples, and
// a long Levenberg-Marquardt step can land on an alias: every mode is folded back into
// [0, pi / dt].
void FoldAliases(Model& model, double dt) {
  const double sampling = kTwoPi / dt;
  for (int k = 0; k < model.modes; ++k) {
    double w = std::fmod(model.w(k), sampling);
    if (w < 0) w += sampling;
    bool flip = false;
    if (w > 0.5 * sampling) {
      w = sampling - w;
      flip = true;
    }
    model.w(k) = w;
    if (flip) {
      for (int c = 0; c < model.channels; ++c) model.p[model.a_index(c, k) + 1] *= -1;
    }
  }
}

// The parameters' covariance at a solution: the inverse of J^T J (directions it cannot resolve
// get an infinite variance), scaled by the residual variance and inflated by (1 + rho) / (1 - rho)
// for residuals with lag-1 autocorrelation rho.
class ParameterCovariance {
 public:
  ParameterCovariance(const LmResult& fit, const Samples& data) {
    const Model& m = fit.model;
    const int n = static_cast<int>(data.t.size());
    Eigen::MatrixXd jac;
    const Eigen::MatrixXd residual = data.y - EvaluateModel(m, data.t, &jac);
    const int residual_count = n * m.channels;
    const int dof = std::max(1, residual_count - m.size());
    variance_ = fit.rss / dof;
    double lag0 = 0, lag1 = 0;
    for (int c = 0; c < m.channels; ++c) {
      for (int j = 0; j < n; ++j) {
        lag0 += residual(j, c) * residual(j, c);
        if (j + 1 < n && data.index[j + 1] == data.index[j] + 1) {
          lag1 += residual(j, c) * residual(j + 1, c);
        }
      }
    }
    rho_ = lag0 > 0 ? std::clamp(lag1 / lag0, 0.0, 0.95) : 0.0;
    inflation_ = (1 + rho_) / (1 - rho_);
    eig_.compute(NormalMatrix(m, jac));
    const Eigen::VectorXd ev = eig_.eigenvalues();
    const double cutoff = ev.maxCoeff() * 1e-14;
    inv_ev_.resize(ev.size());
    for (int i = 0; i < ev.size(); ++i) {
      inv_ev_[i] = ev[i] > cutoff ? 1.0 / ev[i] : std::numeric_limits<double>::infinity();
    }
  }

  double operator()(int i, int j) const {
    double sum = 0;
    for (int q = 0; q < inv_ev_.size(); ++q) {
      const double vi = eig_.eigenvectors()(i, q), vj = eig_.eigenvectors()(j, q);
      if (vi * vj != 0) sum += vi * vj * inv_ev_[q];
    }
    return sum * variance_ * inflation_;
  }
  double residual_correlation() const { return rho_; }

 private:
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig_;
  Eigen::VectorXd inv_ev_;
  double variance_ = 0.0, rho_ = 0.0, inflation_ = 1.0;
};

// Mode k of a fitted model with its amplitudes and its pole's standard deviations.
FittedMode ModeOf(const Model& m, int k, const ParameterCovariance& covariance) {
  FittedMode mode;
  const int channels = m.channels;
  const double s = m.p[2 * k];
  double w = m.p[2 * k + 1];
  mode.cos_amplitude.resize(channels);
  mode.sin_amplitude.resize(channels);
  mode.channel_amplitude.resize(channels);
  for (int c = 0; c < channels; ++c) {
    mode.cos_amplitude[c] = m.p[m.a_index(c, k)];
    mode.sin_amplitude[c] = m.p[m.a_index(c, k) + 1];
  }
  if (w < 0) {  // the same oscillation with the sine terms negated
    w = -w;
    mode.sin_amplitude = -mode.sin_amplitude;
  }
  for (int c = 0; c < channels; ++c) {
    mode.channel_amplitude[c] = std::hypot(mode.cos_amplitude[c], mode.sin_amplitude[c]);
  }
  mode.amplitude = mode.channel_amplitude.norm();
  const double csw = covariance(2 * k, 2 * k + 1);
  Eigen::Matrix2d cov;
  cov << covariance(2 * k, 2 * k), csw, csw, covariance(2 * k + 1, 2 * k + 1);
  SetPole(s, w, cov, mode);
  return mode;
}

// The fit's report of a selected model: its modes, strongest first, with standard deviations.
DampedSinusoidFit Describe(const LmResult& best, const Samples& data, int candidates) {
  const Model& m = best.model;
  const ParameterCovariance covariance(best, data);
  DampedSinusoidFit out;
  out.candidates = candidates;
  out.converged = best.converged;
  out.iterations = best.iterations;
  out.rms_residual = std::sqrt(best.rss / (static_cast<int>(data.t.size()) * m.channels));
  out.residual_correlation = covariance.residual_correlation();
  out.offsets.resize(m.channels);
  for (int c = 0; c < m.channels; ++c) out.offsets[c] = m.p[m.offset_index(c)];
  for (int k = 0; k < m.modes; ++k) out.modes.push_back(ModeOf(m, k, covariance));
  std::stable_sort(
      out.modes.begin(), out.modes.end(),
      [](const FittedMode& a, const FittedMode& b) { return a.amplitude > b.amplitude; });
  if (!best.converged) out.message = fmt::format("stopped after {} iterations", best.iterations);
  return out;
}

}  // namespace

Eigen::MatrixXd DampedSinusoidFit::Evaluate(const SampledSignal& signal) const {
  Eigen::MatrixXd out(signal.size(), signal.channels());
  for (int c = 0; c < signal.channels(); ++c) {
    out.col(c).setConstant(c < offsets.size() ? offsets[c] : 0.0);
  }
  for (const FittedMode& mode : modes) {
    for (int i = 0; i < signal.size(); ++i) {
      const double t = i * signal.dt;
      const double e = std::exp(-mode.decay_rate * t);
      for (int c = 0; c < signal.channels(); ++c) {
        out(i, c) += e * (mode.cos_amplitude[c] * std::cos(mode.angular_frequency * t) +
                          mode.sin_amplitude[c] * std::sin(mode.angular_frequency * t));
      }
    }
  }
  return out;
}

DampedSinusoidFit FitDampedSinusoids(const SampledSignal& signal, double min_hz, double max_hz,
                                     const EstimatorOptions& options) {
  DampedSinusoidFit out;
  const Samples data = ValidSamples(signal);
  const int n = static_cast<int>(data.t.size());
  if (n < 8) {
    out.message = fmt::format("{} valid samples are too few for a fit", n);
    return out;
  }
  // Candidate poles of the whole record, offered at every step of the selection.
  const PoleFinder finder{signal.dt, min_hz, max_hz, options};
  Eigen::MatrixXd filled = signal.FilledValues();
  filled.rowwise() -= filled.colwise().mean();
  const std::vector<Pole> record_poles = finder.Find(filled);
  out.candidates = static_cast<int>(record_poles.size());

  LmResult best = SelectModes(data, signal.size(), finder, record_poles, options);
  if (best.model.modes == 0) {
    out.message =
        record_poles.empty()
            ? fmt::format("no oscillating pole between {:.2f} and {:.2f} Hz", min_hz, max_hz)
            : "no damped sinusoid explains the record better than a constant";
    return out;
  }
  FoldAliases(best.model, signal.dt);
  return Describe(best, data, out.candidates);
}

namespace {

// A variance's square root. A direction the fit cannot resolve has an infinite variance, and
// infinities of both signs in the propagation sum to NaN: both mean "unknown", an infinite
// standard deviation, never a zero one (which would read as a perfectly certain value).
double StandardDeviation(double variance) {
  if (std::isnan(variance) || variance == std::numeric_limits<double>::infinity()) {
    return std::numeric_limits<double>::infinity();
  }
  return std::sqrt(std::max(0.0, variance));
}

}  // namespace

void SetPole(double decay_rate, double angular_frequency, const Eigen::Matrix2d& covariance,
             FittedMode& mode) {
  const double s = decay_rate, w = angular_frequency, wn = std::hypot(s, w);
  mode.decay_rate = s;
  mode.angular_frequency = w;
  mode.frequency_hz = wn / kTwoPi;
  mode.damping_ratio = s / wn;
  // Propagate the (s, w) covariance to f = wn / 2pi and zeta = s / wn.
  const Eigen::Vector2d df(s / (kTwoPi * wn), w / (kTwoPi * wn));
  const Eigen::Vector2d dz(w * w / (wn * wn * wn), -s * w / (wn * wn * wn));
  mode.frequency_std_hz = StandardDeviation(df.dot(covariance * df));
  mode.damping_std = StandardDeviation(dz.dot(covariance * dz));
}

}  // namespace simtree::identification
