#include "simtree/identification/detail/link_model_choice.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "simtree/identification/detail/joint_poles.h"
#include "simtree/identification/detail/test_signals.h"

namespace simtree::identification {
namespace {

// Estimator (c) on every link alone and on the joint poles, then the choice per link.
struct Readings {
  std::vector<SignalEstimate> own;
  JointPoles joint;
  std::vector<LinkModelChoice> choices;
};

Readings ReadBothWays(const std::vector<SampledSignal>& links) {
  Readings r;
  std::vector<const DampedSinusoidFit*> fits;
  for (const SampledSignal& s : links) {
    r.own.push_back(EstimateModes(s, EstimatorKind::kDampedSinusoidFit));
    EXPECT_EQ(r.own.back().dominant.status, EstimateStatus::kOk) << r.own.back().dominant.message;
  }
  for (const SignalEstimate& e : r.own) fits.push_back(&*e.fit);
  r.joint = EstimateJointPoles(links, {});
  EXPECT_TRUE(r.joint.ok) << r.joint.message;
  r.choices = ChooseLinkModels(links, fits, r.joint.fit);
  return r;
}

DecayRecordOptions Noisy(uint64_t seed, double noise) {
  DecayRecordOptions o;
  o.noise_std = noise;
  o.gap_rate = 0.002;  // ~1% of the samples lost, as a tracker loses them
  o.seed = seed;
  return o;
}

// A tree's modes: two modes 5% apart with one damping, mixed in a different ratio by each of six
// links (their beat outlasts the 10 s record, so each link alone reads them as one decaying
// pole). The shared poles explain every link as well as its own fit with fewer parameters.
TEST(LinkModelChoice, LinksThatShareTheTreesModesReadTheSharedPoles) {
  constexpr double kF1 = 1.058, kF2 = 1.112, kZeta = 0.026;
  for (uint64_t seed : {1, 2}) {
    std::vector<SampledSignal> links;
    for (int k = 0; k < 6; ++k) {
      const double mix = 0.15 + 0.25 * k, a1 = std::cos(mix), a2 = std::sin(mix);
      links.push_back(MakeDecayRecord({{{kF1, kZeta, a1, 0.3 * k}, {kF2, kZeta, a2, 1.1 + 0.5 * k}},
                                       {{kF1, kZeta, 0.4 * a1, 2.0}, {kF2, kZeta, 0.3 * a2, 0.7}}},
                                      Noisy(seed * 100 + k, 0.05)));
    }
    const Readings r = ReadBothWays(links);
    ASSERT_EQ(r.choices.size(), links.size());
    for (size_t k = 0; k < links.size(); ++k) {
      EXPECT_TRUE(r.choices[k].joint)
          << "seed " << seed << " link " << k << ": " << r.choices[k].reason;
    }
  }
}

// Links that ring on their own (each its two planes a few percent apart, drawn inside Table IV's
// ranges): no shared pole fits a link as well as its own, whose frequency the joint fit merged
// with another link's.
TEST(LinkModelChoice, LinksThatRingOnTheirOwnKeepTheirOwnFit) {
  for (uint64_t seed : {1, 2}) {
    IndependentTreeOptions options;
    options.seed = seed;
    const SyntheticMarkerTree tree = MakeIndependentModeTree(options, 10.0, nullptr);
    std::vector<SampledSignal> links;
    for (size_t k = 0; k < tree.links.size(); ++k) {
      // The angles' noise: 2.5 mm of tracker error over a half-metre link.
      links.push_back(MakeDecayRecord({tree.links[k].theta_u, tree.links[k].theta_w},
                                      Noisy(seed * 100 + k, 0.005)));
    }
    const Readings r = ReadBothWays(links);
    ASSERT_EQ(r.choices.size(), links.size());
    const int own = static_cast<int>(std::count_if(
        r.choices.begin(), r.choices.end(), [](const LinkModelChoice& c) { return !c.joint; }));
    std::string reasons;
    for (const LinkModelChoice& c : r.choices) reasons += "\n  " + c.reason;
    EXPECT_GE(own, 5) << "seed " << seed << reasons;
  }
}

}  // namespace
}  // namespace simtree::identification
