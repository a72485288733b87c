#include "simtree/identification/detail/shared_pole_uncertainty.h"

#include <algorithm>
#include <cmath>

namespace simtree::identification {
namespace {

// sqrt(s^2 + max(0, d^2 - s_own^2 - s^2)): an infinite own deviation says nothing of the bias.
double Widened(double value, double std, double own_value, double own_std) {
  const double d = own_value - value;
  const double excess = d * d - own_std * own_std - std * std;
  return std::isfinite(excess) && excess > 0 ? std::sqrt(std * std + excess) : std;
}

void Widen(const ModalEstimate& own, ModalEstimate& e) {
  if (e.status != EstimateStatus::kOk || own.status != EstimateStatus::kOk) return;
  e.frequency_std_hz =
      Widened(e.frequency_hz, e.frequency_std_hz, own.frequency_hz, own.frequency_std_hz);
  e.damping_std = Widened(e.damping_ratio, e.damping_std, own.damping_ratio, own.damping_std);
}

}  // namespace

void WidenBySharedMisfit(const SignalEstimate& own, SignalEstimate& shared) {
  Widen(own.dominant, shared.dominant);
  for (size_t c = 0; c < shared.per_channel.size() && c < own.per_channel.size(); ++c) {
    Widen(own.per_channel[c], shared.per_channel[c]);
  }
}

}  // namespace simtree::identification
