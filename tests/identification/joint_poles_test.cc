#include "simtree/identification/detail/joint_poles.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/identification/detail/test_signals.h"

namespace simtree::identification {
namespace {

double RelativeError(double estimate, double truth) { return std::abs(estimate / truth - 1.0); }

// Two modes 5% apart (beat period 18.5 s, longer than the 10 s record) with the same damping,
// mixed in a different ratio by each of six links, 30 fps, 2% noise: the magnolia's case.
constexpr double kF1 = 1.058, kF2 = 1.112, kZeta = 0.026;

std::vector<SampledSignal> CloseModeLinks(uint64_t seed, double noise) {
  std::vector<SampledSignal> links;
  for (int k = 0; k < 6; ++k) {
    const double mix = 0.15 + 0.25 * k;  // radians: from mostly mode 1 to mostly mode 2
    DecayRecordOptions o;
    o.noise_std = noise;
    o.seed = seed * 100 + k;
    const double a1 = std::cos(mix), a2 = std::sin(mix);
    links.push_back(MakeDecayRecord({{{kF1, kZeta, a1, 0.3 * k}, {kF2, kZeta, a2, 1.1 + 0.5 * k}},
                                     {{kF1, kZeta, 0.4 * a1, 2.0}, {kF2, kZeta, 0.3 * a2, 0.7}}},
                                    o));
  }
  return links;
}

// Each link alone reads the beat of the two modes partly as decay; all six links at once pin
// both poles.
TEST(JointPoles, CloseModesMixedDifferentlyByEachLinkAreResolvedTogether) {
  for (uint64_t seed : {1, 2, 3}) {
    const std::vector<SampledSignal> links = CloseModeLinks(seed, 0.1);
    const JointPoles joint = EstimateJointPoles(links, {});
    ASSERT_TRUE(joint.ok) << joint.message;
    ASSERT_EQ(joint.links.size(), links.size());
    double worst_own = 0, worst_joint = 0;
    for (size_t k = 0; k < links.size(); ++k) {
      const ModalEstimate own = EstimateModes(links[k], EstimatorKind::kDampedSinusoidFit).dominant;
      const ModalEstimate& e = joint.links[k].dominant;
      ASSERT_EQ(own.status, EstimateStatus::kOk) << own.message;
      ASSERT_EQ(e.status, EstimateStatus::kOk) << e.message;
      // The dominant mode is the one the link mixes in more.
      const double truth_f = k < 3 ? kF1 : kF2;
      EXPECT_LT(RelativeError(e.frequency_hz, truth_f), 0.005) << "seed " << seed << " link " << k;
      EXPECT_LT(RelativeError(e.damping_ratio, kZeta), 0.12) << "seed " << seed << " link " << k;
      EXPECT_TRUE(std::isfinite(e.damping_std) && e.damping_std > 0);
      worst_own = std::max(worst_own, RelativeError(own.damping_ratio, kZeta));
      worst_joint = std::max(worst_joint, RelativeError(e.damping_ratio, kZeta));
    }
    EXPECT_GT(worst_own, 1.5 * worst_joint) << "seed " << seed;
  }
}

// One principal component carries both modes 5% apart, and at 30% noise a fit to it alone takes
// them for one pole whose damping absorbs their beat. Offered split and refined on every link,
// the pair comes back apart.
TEST(JointPoles, APairMergedOnTheComponentsIsSplitOnTheLinks) {
  for (uint64_t seed : {1, 2}) {
    const std::vector<SampledSignal> links = CloseModeLinks(seed, 0.3);
    JointPolesOptions options;
    options.components = 1;
    options.split_merged_poles = false;
    const JointPoles merged = EstimateJointPoles(links, {}, options);
    options.split_merged_poles = true;
    const JointPoles split = EstimateJointPoles(links, {}, options);
    ASSERT_TRUE(merged.ok && split.ok) << merged.message << " / " << split.message;
    auto poles = [](const JointPoles& j) {
      std::string text;
      for (const FittedMode& m : j.fit.modes) {
        text += fmt::format(" {:.4f} Hz {:.4f}", m.frequency_hz, m.damping_ratio);
      }
      return text;
    };
    // A pole within 0.5% of f, and with damping within `zeta_tolerance` when one is given.
    auto found = [](const JointPoles& j, double f, double zeta_tolerance) {
      return std::any_of(j.fit.modes.begin(), j.fit.modes.end(), [&](const FittedMode& m) {
        return RelativeError(m.frequency_hz, f) < 0.005 &&
               RelativeError(m.damping_ratio, kZeta) < zeta_tolerance;
      });
    };
    constexpr double kAny = 1e9;
    EXPECT_FALSE(found(merged, kF1, kAny) && found(merged, kF2, kAny))
        << "seed " << seed << poles(merged);
    EXPECT_TRUE(found(split, kF1, 0.35) && found(split, kF2, 0.35))
        << "seed " << seed << poles(split);
    EXPECT_EQ(split.splits, 1) << split.message;
  }
}

TEST(JointPoles, RecordsOnDifferentGridsAreRefused) {
  std::vector<SampledSignal> links = CloseModeLinks(1, 0.02);
  links[1] = links[1].Slice(0, links[1].size() - 1);
  EXPECT_THROW(EstimateJointPoles(links, {}), std::invalid_argument);
}

}  // namespace
}  // namespace simtree::identification
