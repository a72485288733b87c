#include "simtree/identification/detail/link_model_choice.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/QR>

namespace simtree::identification {
namespace {

// A link's valid samples and the joint poles' columns on them (cos, sin per pole).
struct LinkDesign {
  Eigen::MatrixXd y;      // valid samples x channels
  Eigen::MatrixXd poles;  // valid samples x 2 per joint pole
  std::vector<int> rows;  // sample index of each valid sample
};

LinkDesign DesignOf(const SampledSignal& signal, const DampedSinusoidFit& joint) {
  LinkDesign d;
  for (int i = 0; i < signal.size(); ++i) {
    if (signal.valid[i]) d.rows.push_back(i);
  }
  const int n = static_cast<int>(d.rows.size());
  const int modes = static_cast<int>(joint.modes.size());
  d.y.resize(n, signal.channels());
  d.poles.resize(n, 2 * modes);
  for (int j = 0; j < n; ++j) {
    const double t = d.rows[j] * signal.dt;
    d.y.row(j) = signal.values.row(d.rows[j]);
    for (int k = 0; k < modes; ++k) {
      const FittedMode& m = joint.modes[k];
      const double e = std::exp(-m.decay_rate * t);
      d.poles(j, 2 * k) = e * std::cos(m.angular_frequency * t);
      d.poles(j, 2 * k + 1) = e * std::sin(m.angular_frequency * t);
    }
  }
  return d;
}

// The residual of an offset and the poles `selected` by linear least squares.
Eigen::MatrixXd Residual(const LinkDesign& d, const std::vector<int>& selected) {
  Eigen::MatrixXd x(d.y.rows(), 1 + 2 * selected.size());
  x.col(0).setOnes();
  for (size_t s = 0; s < selected.size(); ++s) {
    x.middleCols(1 + 2 * s, 2) = d.poles.middleCols(2 * selected[s], 2);
  }
  return d.y - x * x.colPivHouseholderQr().solve(d.y);
}

// Lag-1 autocorrelation of a residual over consecutive valid samples, clamped to [0, 0.95].
double Lag1(const Eigen::MatrixXd& r, const std::vector<int>& rows) {
  double lag0 = r.squaredNorm(), lag1 = 0.0;
  for (size_t j = 0; j + 1 < rows.size(); ++j) {
    if (rows[j + 1] == rows[j] + 1) lag1 += r.row(j).dot(r.row(j + 1));
  }
  return lag0 > 0 ? std::clamp(lag1 / lag0, 0.0, 0.95) : 0.0;
}

double Bic(double rss, double n, double count, double parameters) {
  return count * std::log(std::max(rss, 1e-300) / n) + parameters * std::log(count);
}

// The joint poles that explain this link: forward selection by BIC on all n residuals (as the
// own fit chose its poles), two parameters per pole besides the amplitudes.
std::vector<int> SelectPoles(const LinkDesign& d, int modes) {
  const double n = static_cast<double>(d.y.size());
  const int channels = static_cast<int>(d.y.cols());
  std::vector<int> selected;
  double best = Bic(Residual(d, selected).squaredNorm(), n, n, channels);
  while (static_cast<int>(selected.size()) < modes) {
    int pick = -1;
    double pick_bic = best;
    for (int k = 0; k < modes; ++k) {
      if (std::find(selected.begin(), selected.end(), k) != selected.end()) continue;
      std::vector<int> trial = selected;
      trial.push_back(k);
      const double parameters = channels * (1.0 + 2.0 * trial.size()) + 2.0 * trial.size();
      const double bic = Bic(Residual(d, trial).squaredNorm(), n, n, parameters);
      if (bic < pick_bic) {
        pick_bic = bic;
        pick = k;
      }
    }
    if (pick < 0) break;
    selected.push_back(pick);
    best = pick_bic;
  }
  return selected;
}

}  // namespace

std::vector<LinkModelChoice> ChooseLinkModels(const std::vector<SampledSignal>& signals,
                                              const std::vector<const DampedSinusoidFit*>& own,
                                              const DampedSinusoidFit& joint) {
  const int modes = static_cast<int>(joint.modes.size());
  std::vector<LinkDesign> designs;
  std::vector<std::vector<int>> selected;
  std::vector<int> sharing(modes, 0);  // links that select each pole
  for (const SampledSignal& s : signals) {
    designs.push_back(DesignOf(s, joint));
    selected.push_back(SelectPoles(designs.back(), modes));
    for (int k : selected.back()) ++sharing[k];
  }
  std::vector<LinkModelChoice> out;
  for (size_t i = 0; i < signals.size(); ++i) {
    const LinkDesign& d = designs[i];
    const double n = static_cast<double>(d.y.size());
    const int channels = static_cast<int>(d.y.cols());
    LinkModelChoice c;
    const Eigen::MatrixXd r = Residual(d, selected[i]);
    const double joint_rss = r.squaredNorm();
    const double own_rss = own[i]->rms_residual * own[i]->rms_residual * n;
    const double own_rho = std::clamp(own[i]->residual_correlation, 0.0, 0.95);
    const double rho = joint_rss < own_rss ? Lag1(r, d.rows) : own_rho;
    c.effective_samples = std::max(2.0, n * (1 - rho) / (1 + rho));
    c.own_modes = static_cast<int>(own[i]->modes.size());
    c.joint_modes = static_cast<int>(selected[i].size());
    c.own_rms = own[i]->rms_residual;
    c.joint_rms = n > 0 ? std::sqrt(joint_rss / n) : 0.0;
    double shared = 0.0;
    for (int k : selected[i]) shared += 2.0 / sharing[k];
    const double own_parameters = 2.0 * c.own_modes + channels * (1.0 + 2.0 * c.own_modes);
    const double joint_parameters = shared + channels * (1.0 + 2.0 * c.joint_modes);
    c.own_bic = Bic(own_rss, n, c.effective_samples, own_parameters);
    c.joint_bic = Bic(joint_rss, n, c.effective_samples, joint_parameters);
    c.joint = c.joint_bic <= c.own_bic;
    c.reason = fmt::format(
        "{}: BIC {:.1f} (shared, {} of {} poles, rms {:.3g}) {} {:.1f} (own, {} poles, rms "
        "{:.3g}) on {:.0f} effective samples",
        c.joint ? "shared poles" : "own poles", c.joint_bic, c.joint_modes, modes, c.joint_rms,
        c.joint ? "<=" : ">", c.own_bic, c.own_modes, c.own_rms, c.effective_samples);
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace simtree::identification
