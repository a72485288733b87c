#include "simtree/identification/detail/shared_pole_uncertainty.h"

#include <cmath>

#include <gtest/gtest.h>

namespace simtree::identification {
namespace {

ModalEstimate Value(double f, double f_std, double zeta, double zeta_std) {
  ModalEstimate e;
  e.frequency_hz = f;
  e.frequency_std_hz = f_std;
  e.damping_ratio = zeta;
  e.damping_std = zeta_std;
  return e;
}

SignalEstimate Reading(const ModalEstimate& dominant) {
  SignalEstimate s;
  s.dominant = dominant;
  s.per_channel = {dominant, dominant};
  return s;
}

// A shared value the link's own fit agrees with, within their deviations, keeps the stack's.
TEST(SharedPoleUncertainty, AgreementKeepsTheStacksDeviations) {
  SignalEstimate shared = Reading(Value(1.000, 0.001, 0.030, 0.001));
  WidenBySharedMisfit(Reading(Value(1.002, 0.003, 0.031, 0.002)), shared);
  EXPECT_DOUBLE_EQ(shared.dominant.frequency_std_hz, 0.001);
  EXPECT_DOUBLE_EQ(shared.dominant.damping_std, 0.001);
  EXPECT_DOUBLE_EQ(shared.dominant.frequency_hz, 1.000);
}

// Beyond them, the excess is the shared value's bias for this link: each value on its own, every
// plane too, no value changed.
TEST(SharedPoleUncertainty, DisagreementBeyondTheDeviationsWidensThem) {
  SignalEstimate shared = Reading(Value(1.000, 0.001, 0.030, 0.001));
  WidenBySharedMisfit(Reading(Value(1.020, 0.003, 0.031, 0.002)), shared);
  const double expected = std::sqrt(0.001 * 0.001 + 0.02 * 0.02 - 0.003 * 0.003 - 0.001 * 0.001);
  EXPECT_NEAR(shared.dominant.frequency_std_hz, expected, 1e-12);
  EXPECT_DOUBLE_EQ(shared.dominant.damping_std, 0.001);
  for (const ModalEstimate& plane : shared.per_channel) {
    EXPECT_NEAR(plane.frequency_std_hz, expected, 1e-12);
  }
  EXPECT_DOUBLE_EQ(shared.dominant.frequency_hz, 1.000);
  EXPECT_DOUBLE_EQ(shared.dominant.damping_ratio, 0.030);
}

// An own value without a deviation (its covariance broke down) or without a value at all says
// nothing of the shared value's bias.
TEST(SharedPoleUncertainty, AnOwnValueWithoutDeviationOrStatusLeavesItAlone) {
  SignalEstimate shared = Reading(Value(1.000, 0.001, 0.030, 0.001));
  SignalEstimate own = Reading(Value(1.100, INFINITY, 0.060, 0.002));
  own.per_channel[1].status = EstimateStatus::kTooShort;
  WidenBySharedMisfit(own, shared);
  EXPECT_DOUBLE_EQ(shared.dominant.frequency_std_hz, 0.001);
  EXPECT_NEAR(shared.dominant.damping_std, std::sqrt(0.03 * 0.03 - 0.002 * 0.002), 1e-12);
  EXPECT_DOUBLE_EQ(shared.per_channel[1].damping_std, 0.001);
}

}  // namespace
}  // namespace simtree::identification
