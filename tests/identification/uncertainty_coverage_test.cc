// The standard deviations the fit reports against the truth on seeded records (issue 23): about
// 68% of true values should lie within one standard deviation; 60-80% is what the issue asks.

#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "simtree/identification/detail/test_signals.h"
#include "simtree/identification/identify.h"
#include "simtree/tracking/tracker_error.h"

namespace simtree::identification {
namespace {

struct Coverage {
  int values = 0, frequency = 0, damping = 0;
  double FrequencyShare() const { return values ? double(frequency) / values : 0.0; }
  double DampingShare() const { return values ? double(damping) / values : 0.0; }
  void Add(const ModalEstimate& e, const DampedSinusoid& truth) {
    if (e.status != EstimateStatus::kOk || !std::isfinite(e.frequency_std_hz) ||
        !std::isfinite(e.damping_std)) {
      return;
    }
    ++values;
    frequency += std::abs(e.frequency_hz - truth.frequency_hz) <= e.frequency_std_hz;
    damping += std::abs(e.damping_ratio - truth.damping_ratio) <= e.damping_std;
  }
};

// Two planes of one mode each under white noise, the model the fit assumes: its standard
// deviations are those of the noise alone.
TEST(UncertaintyCoverage, OneModePerPlaneUnderWhiteNoise) {
  Coverage c;
  for (int seed = 1; seed <= 60; ++seed) {
    // Table IV's ranges, f 0.72-1.50 Hz and zeta 0.022-0.060, swept.
    const double f = 0.72 + 0.013 * seed, zeta = 0.022 + 0.038 * ((seed * 7) % 60) / 60.0;
    const DampedSinusoid mode{f, zeta, 1.0, 0.3 * seed};
    DecayRecordOptions options;
    options.noise_std = 0.05;
    options.gap_rate = 0.01;
    options.seed = seed;
    const SampledSignal record =
        MakeDecayRecord({{mode}, {{f, zeta, 0.5, 1.0 + 0.1 * seed}}}, options);
    c.Add(EstimateModes(record, EstimatorKind::kDampedSinusoidFit).dominant, mode);
  }
  std::printf("white noise: %d values, f %.0f%%, zeta %.0f%%\n", c.values, 100 * c.FrequencyShare(),
              100 * c.DampingShare());
  ASSERT_GE(c.values, 57);
  EXPECT_GE(c.FrequencyShare(), 0.55);
  EXPECT_LE(c.FrequencyShare(), 0.85);
  EXPECT_GE(c.DampingShare(), 0.55);
  EXPECT_LE(c.DampingShare(), 0.85);
}

// Independent-mode trees (each link its own two close modes, children riding on their parents)
// through a tracker's errors, every link on its own fit.
TEST(UncertaintyCoverage, PerLinkFitsOnIndependentModeTrees) {
  Coverage c;
  for (int seed = 1; seed <= 6; ++seed) {
    IndependentTreeOptions tree_options;
    tree_options.seed = 100 + seed;
    std::vector<DampedSinusoid> truth;
    const SyntheticMarkerTree tree = MakeIndependentModeTree(tree_options, 10.0, &truth);
    std::vector<MarkerLink> markers;
    tracking::TrackerErrorOptions error;
    error.seed = 100 + seed;
    const Trajectories tracks =
        tracking::SimulateTrackerError(MakeMarkerTrajectories(tree, 30, 2, 10, &markers), error);
    IdentifyOptions options;
    options.window_s = 10;
    options.joint_poles = false;
    options.compare_estimators = false;
    for (const LinkIdentification& link : IdentifyMaterials(tracks, markers, options).links) {
      c.Add(link.value, truth[link.deflection.link.child]);
    }
  }
  std::printf("independent modes, per link: %d values, f %.0f%%, zeta %.0f%%\n", c.values,
              100 * c.FrequencyShare(), 100 * c.DampingShare());
  ASSERT_GE(c.values, 36);
  EXPECT_GE(c.FrequencyShare(), 0.55);
  EXPECT_LE(c.FrequencyShare(), 0.85);
  EXPECT_GE(c.DampingShare(), 0.55);
  EXPECT_LE(c.DampingShare(), 0.85);
}

}  // namespace
}  // namespace simtree::identification
