#include "simtree/synth/detail/fem_truth.h"

#include <cmath>
#include <complex>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "synth/fem_test_trees.h"

namespace simtree::synth {
namespace {

using ::testing::HasSubstr;

Marker MakeMarker(const Tree& tree, int id, int branch, double arc_length, int parent) {
  return {id,     fmt::format("M{}", id),
          branch, arc_length,
          parent, tree.branches[branch].PointAt(arc_length)};
}

// The static deflection under a tip force, at rest: what a held pull leaves at release.
FemState HeldState(const FemModel& model, int branch, const Eigen::Vector3d& force) {
  FemState s = RestState(model);
  s.x = SolveStatic(model, model.PointLoad(branch, model.tree().branches[branch].Length(), force));
  return s;
}

// The Y (1 m children of 2 cm) with a marker on the trunk and one near each child's tip, held
// pulled sideways by child 1's tip.
struct PulledY {
  Tree tree = Marked(test::YTree(0.08, 0.02));
  WoodProperties wood = DampedWood();
  FemModel model{tree, wood};
  ModalBasis modes = ComputeModes(model, {.count = 20});
  FemState held = HeldState(model, 1, {0, 20, 0});

  static Tree Marked(Tree t) {
    t.markers = {MakeMarker(t, 0, 0, 0.5, -1), MakeMarker(t, 1, 1, 0.9, 0),
                 MakeMarker(t, 2, 2, 0.9, 0)};
    return t;
  }
  static WoodProperties DampedWood() {
    WoodProperties w = test::TestWood();
    w.SetRayleighFromRatios(1.0, 0.04, 30.0, 0.03);
    return w;
  }
};

// A single cantilever with a marker at mid-length (the root) and one at the tip: released from a
// tip pull, every signal is dominated by the first bending mode.
TEST(FemTruth, CantileverMarkersSeeTheFirstMode) {
  Tree tree = test::UniformCantilever({0, 0, 1}, 2.0, 0.02, 20);
  tree.markers = {MakeMarker(tree, 0, 0, 1.0, -1), MakeMarker(tree, 1, 0, 2.0, 0)};
  WoodProperties wood = test::TestWood();
  wood.SetRayleighFromRatios(1.0, 0.04, 30.0, 0.03);
  const FemModel model(tree, wood);
  const ModalBasis modes = ComputeModes(model, {.count = 12});
  const ModalTruth truth = ComputeModalTruth(model, modes, tree, HeldState(model, 0, {10, 0, 0}));
  EXPECT_EQ(truth.source, "fem");
  ASSERT_EQ(truth.modes.size(), 12u);
  // Every mode carries its effective-mass fractions (fem_effective_mass.h): the first bending
  // pair each about 61% of the horizontal mass, so the lowest sway mode is the first.
  for (const ModalTruth::TreeMode& m : truth.modes) {
    ASSERT_TRUE(m.horizontal_mass_fraction.has_value());
    ASSERT_TRUE(m.torsion_mass_fraction.has_value());
  }
  EXPECT_NEAR(*truth.modes[0].horizontal_mass_fraction, 0.613, 0.02);
  EXPECT_EQ(truth.lowest_sway_mode, 0);
  const double f1 = test::CantileverFrequencyHz(test::kBetaL1, wood, 2.0, 0.02);
  ASSERT_EQ(truth.links.size(), 2u);
  EXPECT_EQ(truth.links[0].parent, -1);  // the root marker's displacement first
  EXPECT_EQ(truth.links[0].child, 0);
  EXPECT_EQ(truth.links[1].parent, 0);
  EXPECT_EQ(truth.links[1].child, 1);
  for (const ModalTruth::Link& link : truth.links) {
    EXPECT_NEAR(link.frequency_hz / f1, 1.0, 1e-2) << link.child;
    EXPECT_NEAR(link.damping_ratio, wood.DampingRatioAt(link.frequency_hz), 1e-12);
    ASSERT_EQ(link.peaks.size(), 2u);
    EXPECT_LE(link.peaks[0].mode, 1);  // one of the two planes' first mode
    EXPECT_GT(link.peaks[0].strength, 10 * link.peaks[1].strength);
    EXPECT_GT(link.peaks[0].amplitude, 0.0);
  }
  ASSERT_EQ(truth.branches.size(), 1u);
  EXPECT_NEAR(truth.branches[0].frequency_hz / f1, 1.0, 1e-2);
  // The root marker's amplitude is the first mode's share of its static deflection (metres):
  // P phi(L/2) phi(L) / (rho A L omega^2) with the closed-form shape
  // phi(x) = cosh bx - cos bx - s (sinh bx - sin bx), s = (cosh b + cos b) / (sinh b + sin b),
  // which is normalised so that the mean of phi^2 over the length is 1 (and phi(L) = 2).
  const double b = test::kBetaL1;
  const double s = (std::cosh(b) + std::cos(b)) / (std::sinh(b) + std::sin(b));
  const auto phi = [&](double x) {
    return std::cosh(b * x) - std::cos(b * x) - s * (std::sinh(b * x) - std::sin(b * x));
  };
  const double rho_a_l = wood.density_kg_m3 * kPi * 0.02 * 0.02 * 2.0;
  const double omega = kTwoPi * f1;
  EXPECT_NEAR(
      truth.links[0].peaks[0].amplitude / (10.0 * phi(0.5) * phi(1.0) / (rho_a_l * omega * omega)),
      1.0, 1e-3);
}

// On the Y, a pulled child's link and branch see the children's modes. Pulled sideways, one
// child holds the in-phase and the out-of-phase mode of the pair nearly equally; the other child
// starts almost at rest, where the two cancel, and its peak there is the weaker.
TEST(FemTruth, YTreeChildrenSeeTheirPairedModes) {
  const PulledY y;
  const Tree& tree = y.tree;
  const WoodProperties& wood = y.wood;
  const ModalBasis& modes = y.modes;
  const ModalTruth truth = ComputeModalTruth(y.model, modes, tree, y.held);
  ASSERT_EQ(truth.branches.size(), 3u);
  ASSERT_EQ(truth.links.size(), 3u);
  const double child_f1 = test::CantileverFrequencyHz(test::kBetaL1, wood, 1.0, 0.02);
  for (int b : {1, 2}) {
    EXPECT_NEAR(truth.branches[b].frequency_hz / child_f1, 1.0, 0.15) << b;
    EXPECT_NEAR(truth.links[b].frequency_hz / child_f1, 1.0, 0.15) << b;
    // The runner-up is the pair's other mode, nearly as strong.
    const auto& peaks = truth.branches[b].peaks;
    ASSERT_EQ(peaks.size(), 2u);
    EXPECT_NEAR(peaks[1].frequency_hz / peaks[0].frequency_hz, 1.0, 0.05);
    EXPECT_GT(peaks[1].strength, 0.5 * peaks[0].strength);
  }
  EXPECT_LT(truth.branches[2].peaks[0].strength, 0.8 * truth.branches[1].peaks[0].strength);
  // Links and branches name existing modes.
  for (const auto& l : truth.links) {
    ASSERT_FALSE(l.peaks.empty());
    EXPECT_EQ(l.frequency_hz, truth.modes[l.peaks[0].mode].frequency_hz);
  }
}

// The closed form against Simpson's rule on the decay itself, at, near and far from its frequency.
TEST(FemTruth, DecayFourierIntegralMatchesQuadrature) {
  const double omega = kTwoPi * 1.3, zeta = 0.04, a = 0.7, b = -0.3, record = 10.0;
  const double wd = omega * std::sqrt(1 - zeta * zeta);
  for (double at : {wd, 0.97 * wd, 2.5 * wd, 0.0}) {
    const int n = 200000;
    std::complex<double> sum = 0.0;
    for (int k = 0; k <= n; ++k) {
      const double t = record * k / n;
      const double q = std::exp(-zeta * omega * t) * (a * std::cos(wd * t) + b * std::sin(wd * t));
      const double w = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
      sum += w * q * std::exp(std::complex<double>(0, -at * t));
    }
    sum *= record / n / 3.0;
    EXPECT_NEAR(std::abs(DecayFourierIntegral(omega, zeta, a, b, at, record) - sum), 0.0,
                1e-9 * (1 + std::abs(sum)))
        << at;
  }
  // At its own frequency, a lone mode's peak is half its amplitude times the envelope's integral.
  const double peak = 2 * std::abs(DecayFourierIntegral(omega, zeta, a, b, wd, record));
  // (up to the negative frequency's share, about zeta / 2)
  EXPECT_NEAR(peak / (std::hypot(a, b) * (1 - std::exp(-zeta * omega * record)) / (zeta * omega)),
              1.0, 0.03);
}

// On the Y pulled by one child, the other child starts almost at rest: the pair's in-phase and
// out-of-phase modes cancel in its signal at release and part as they beat. A record too short
// to resolve the pair sees little of it there; a long one sees both children alike.
TEST(FemTruth, CloseModesThatCancelMakeNoPeakInAShortRecord) {
  const PulledY y;
  const auto strength_ratio = [&](double record) {
    const ModalTruth truth =
        ComputeModalTruth(y.model, y.modes, y.tree, y.held, {.record_after_release_s = record});
    const auto& pulled = truth.branches[1].peaks;
    const auto& other = truth.branches[2].peaks;
    double other_at_pair = 0.0;
    for (const auto& p : other) {
      if (std::abs(p.frequency_hz / pulled[0].frequency_hz - 1) < 0.05) {
        other_at_pair = std::max(other_at_pair, p.strength);
      }
    }
    return other_at_pair / pulled[0].strength;
  };
  // The pair (15.9-16.7 Hz, zeta 0.018) decays in about 0.6 s: the other child's share grows
  // over the first second and stays where the decay leaves it.
  const double short_ratio = strength_ratio(0.05);
  const double long_ratio = strength_ratio(20.0);
  EXPECT_LT(short_ratio, 0.15);
  EXPECT_GT(long_ratio, 3 * short_ratio);
  EXPECT_NEAR(strength_ratio(5.0) / long_ratio, 1.0, 0.01);
}

TEST(FemTruth, BadInputIsAnInputError) {
  Tree tree = test::UniformCantilever({0, 0, 1}, 1.0, 0.02, 10);
  tree.markers = {MakeMarker(tree, 0, 0, 0.5, -1), MakeMarker(tree, 1, 0, 0.5, 0)};
  const FemModel model(tree, test::TestWood());
  const ModalBasis modes = ComputeModes(model, {.count = 4});
  const FemState held = HeldState(model, 0, {1, 0, 0});
  try {
    ComputeModalTruth(model, modes, tree, held);
    FAIL() << "coincident markers accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("coincide"));
  }
  tree.markers[1].arc_length = 1.0;
  tree.markers[1].position = tree.branches[0].tip().position;
  FemState bad = held;
  bad.v.resize(3);
  EXPECT_THROW(ComputeModalTruth(model, modes, tree, bad), InputError);
  EXPECT_THROW(ComputeModalTruth(model, modes, test::YTree(), held), InputError);
  EXPECT_THROW(ComputeModalTruth(model, modes, tree, held, {.record_after_release_s = 0}),
               InputError);
  EXPECT_NO_THROW(ComputeModalTruth(model, modes, tree, held));
}

}  // namespace
}  // namespace simtree::synth
