#include "simtree/identification/detail/branch_modes.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "simtree/core/option_checks.h"

namespace simtree::identification {
namespace {

// Estimator (c)'s peak over the record: amplitude times the integral of the envelope.
double Strength(double amplitude, double decay_rate, double record_s) {
  return amplitude * (decay_rate * record_s > 1e-9
                          ? (1.0 - std::exp(-decay_rate * record_s)) / decay_rate
                          : record_s);
}

// The parent's share of the same joint pole (same frequency and damping: the poles are shared).
double ParentShare(const std::vector<LinkModeShare>& parent, const LinkModeShare& mode) {
  for (const LinkModeShare& p : parent) {
    if (std::abs(p.frequency_hz - mode.frequency_hz) <= 1e-9 * mode.frequency_hz &&
        std::abs(p.damping_ratio - mode.damping_ratio) <= 1e-9) {
      return p.share;
    }
  }
  return 0.0;
}

ModalEstimate EstimateOf(const LinkModeShare& mode, int channel) {
  ModalEstimate e;
  e.frequency_hz = mode.frequency_hz;
  e.damping_ratio = mode.damping_ratio;
  e.frequency_std_hz = mode.frequency_std_hz;
  e.damping_std = mode.damping_std;
  e.amplitude = channel < 0 ? mode.amplitude : mode.plane_amplitude[channel];
  e.channel = channel;
  return e;
}

}  // namespace

void BranchModeOptions::Validate() const {
  CheckShare("min_share", min_share);
  CheckAtLeast("max_participation", max_participation, 1.0);
}

std::vector<LinkModeShare> ModeShares(const DampedSinusoidFit& fit, double record_s, double min_hz,
                                      double max_hz, double max_damping_ratio) {
  std::vector<LinkModeShare> out;
  for (const FittedMode& m : fit.modes) {
    if (m.frequency_hz < min_hz || m.frequency_hz > max_hz || m.damping_ratio <= 0 ||
        m.damping_ratio > max_damping_ratio) {
      continue;
    }
    LinkModeShare s;
    s.frequency_hz = m.frequency_hz;
    s.damping_ratio = m.damping_ratio;
    s.frequency_std_hz = m.frequency_std_hz;
    s.damping_std = m.damping_std;
    s.amplitude = m.amplitude;
    for (int c = 0; c < 2 && c < m.channel_amplitude.size(); ++c) {
      s.plane_amplitude[c] = m.channel_amplitude[c];
    }
    s.strength = Strength(m.amplitude, m.decay_rate, record_s);
    out.push_back(s);
  }
  std::stable_sort(out.begin(), out.end(), [](const LinkModeShare& a, const LinkModeShare& b) {
    return a.strength > b.strength;
  });
  for (LinkModeShare& s : out) s.share = s.strength / out.front().strength;
  return out;
}

std::vector<BranchMode> ChooseBranchModes(std::vector<std::vector<LinkModeShare>>& links,
                                          const std::vector<int>& parent,
                                          const BranchModeOptions& options) {
  options.Validate();
  std::vector<BranchMode> out(links.size());
  for (size_t i = 0; i < links.size(); ++i) {
    BranchMode& b = out[i];
    b.value.status = EstimateStatus::kFailed;
    if (links[i].empty()) {
      b.why = "no joint pole";
      continue;
    }
    const bool has_parent = parent[i] >= 0;
    for (LinkModeShare& m : links[i]) {
      if (!has_parent) continue;
      const double p = ParentShare(links[parent[i]], m);
      m.participation =
          p > 0 ? std::min(m.share / p, options.max_participation) : options.max_participation;
    }
    const LinkModeShare* most = nullptr;
    for (const LinkModeShare& m : links[i]) {
      if (has_parent && m.share >= options.min_share &&
          (!most || m.participation > most->participation)) {
        most = &m;
      }
    }
    const LinkModeShare* best = options.by_participation && most ? most : &links[i].front();
    b.value = EstimateOf(*best, -1);
    b.participation = best->participation;
    b.strongest = best == &links[i].front();
    if (most) b.most_participating_hz = most->frequency_hz;
    for (int c = 0; c < 2; ++c) b.planes[c] = EstimateOf(*best, c);
    b.why = !has_parent ? "the link's strongest pole (no measured parent)"
            : !most
                ? "the link's strongest pole"
                : fmt::format(
                      "{} pole {:.3f} Hz (participation {:.2f}); most participating {:.3f} Hz "
                      "(participation {:.2f}, share {:.2f})",
                      b.strongest ? "the strongest" : "the most participating", best->frequency_hz,
                      best->participation, most->frequency_hz, most->participation, most->share);
  }
  return out;
}

}  // namespace simtree::identification
