#include "simtree/synth/detail/fem_effective_mass.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/core/units.h"
#include "synth/fem_test_trees.h"

namespace simtree::synth {
namespace {

using ::testing::HasSubstr;

// A uniform vertical cantilever, 2 m long, radius 2 cm, in 100 elements (600 degrees of freedom,
// solved densely): the classic effective masses of a clamped-free beam and shaft.
//   - First bending pair: each carries 0.6131 of the mass in its plane (Euler-Bernoulli, the
//     continuum value); the pair carries it in x and in y together, whatever the orientation the
//     eigensolver picks for two modes of one frequency. No torsion.
//   - First torsional mode (sin(pi s / 2L), at sqrt(G / rho) / 4L): 8 / pi^2 = 0.8106 of the
//     polar moment, no horizontal mass.
// The fractions are of the free nodes' mass (the element at the clamp loses its base node's
// share, about half an element's mass of 100), so they agree with the continuum within 1%.
TEST(FemEffectiveMass, UniformVerticalCantileverMatchesTheClassicValues) {
  const WoodProperties wood = test::TestWood();
  const double length = 2.0, radius = 0.02;
  const FemModel model(test::UniformCantilever({0, 0, 1}, length, radius, 20), wood,
                       {.max_element_length_m = 0.02});
  ASSERT_EQ(model.element_count(), 100);
  const ModalBasis modes = ComputeModes(model, {.count = 12});
  ASSERT_EQ(modes.count(), 12);
  const EffectiveMasses masses = ComputeEffectiveMasses(model, modes);
  ASSERT_EQ(masses.count(), 12);

  constexpr double kFirstBending = 0.6131;
  for (int i : {0, 1}) {
    EXPECT_NEAR(masses.horizontal[i], kFirstBending, 0.01) << i;
    EXPECT_LT(masses.torsion[i], 1e-9) << i;
  }
  EXPECT_NEAR(masses.x[0] + masses.x[1], kFirstBending, 0.01);
  EXPECT_NEAR(masses.y[0] + masses.y[1], kFirstBending, 0.01);
  // The second bending pair: 0.1883 each (the continuum value), far below the first.
  for (int i : {2, 3}) EXPECT_NEAR(masses.horizontal[i], 0.1883, 0.01) << i;

  // The first mode that turns the crown is the fixed-free shaft's first torsional mode.
  int torsional = -1;
  for (int i = 0; i < masses.count() && torsional < 0; ++i) {
    if (masses.torsion[i] > 0.5) torsional = i;
  }
  ASSERT_GE(torsional, 0);
  const double torsion_hz = std::sqrt(wood.shear_modulus_pa / wood.density_kg_m3) / (4 * length);
  EXPECT_NEAR(modes.frequency_hz[torsional] / torsion_hz, 1.0, 1e-3);
  EXPECT_NEAR(masses.torsion[torsional], 8.0 / (kPi * kPi), 0.01);
  EXPECT_LT(masses.horizontal[torsional], 1e-9);

  // The base motions' masses: the shaft's mass and polar moment rho (pi r^4 / 2) L, less the
  // clamped node's share of the first element.
  const double mass = wood.density_kg_m3 * kPi * radius * radius * length;
  EXPECT_LT(masses.translating_mass_kg, model.total_mass_kg());
  EXPECT_NEAR(masses.translating_mass_kg / mass, 1.0, 0.01);
  const double polar = wood.density_kg_m3 * kPi * std::pow(radius, 4) / 2.0 * length;
  EXPECT_NEAR(masses.polar_moment_kg_m2 / polar, 1.0, 0.01);

  EXPECT_EQ(LowestSwayMode(masses), 0);
  // No mode carries 90% of the horizontal mass.
  EXPECT_EQ(LowestSwayMode(masses, 0.9), -1);
}

// Over a complete basis the effective masses add up to the base motion's r^T M r: the horizontal
// fractions to 2 (x and y, 1 each), the torsion fractions to 1. A Y of 30 elements (180 degrees
// of freedom, every mode), not symmetric about the vertical through its base in torsion.
TEST(FemEffectiveMass, CompleteBasisAddsUpToTheWholeMass) {
  const FemModel model(test::YTree(), test::TestWood(), {.max_element_length_m = 0.1});
  ASSERT_EQ(model.dof_count(), 180);
  const ModalBasis modes = ComputeModes(model, {.count = model.dof_count()});
  ASSERT_EQ(modes.count(), model.dof_count());
  const EffectiveMasses masses = ComputeEffectiveMasses(model, modes);
  EXPECT_NEAR(masses.x.sum(), 1.0, 1e-8);
  EXPECT_NEAR(masses.y.sum(), 1.0, 1e-8);
  EXPECT_NEAR(masses.horizontal.sum(), 2.0, 1e-8);
  EXPECT_NEAR(masses.torsion.sum(), 1.0, 1e-8);
  EXPECT_GE(masses.horizontal.minCoeff(), 0.0);
  EXPECT_LE(masses.horizontal.maxCoeff(), 1.0 + 1e-9);
  EXPECT_GE(masses.torsion.minCoeff(), 0.0);
  EXPECT_LE(masses.torsion.maxCoeff(), 1.0 + 1e-9);
  EXPECT_GT(masses.translating_mass_kg, 0.9 * model.total_mass_kg());
  EXPECT_LT(masses.translating_mass_kg, model.total_mass_kg());
  EXPECT_GT(masses.polar_moment_kg_m2, 0.0);

  // A truncated basis carries less than the whole.
  const ModalBasis lowest = ComputeModes(model, {.count = 6});
  const EffectiveMasses some = ComputeEffectiveMasses(model, lowest);
  EXPECT_LT(some.horizontal.sum(), 2.0);
  EXPECT_LT(some.torsion.sum(), 1.0);
  for (int i = 0; i < some.count(); ++i) {
    EXPECT_NEAR(some.horizontal[i], masses.horizontal[i], 1e-6) << i;
    EXPECT_NEAR(some.torsion[i], masses.torsion[i], 1e-6) << i;
  }
}

TEST(FemEffectiveMass, ModesOfAnotherModelAreAnInputError) {
  const WoodProperties wood = test::TestWood();
  const FemModel small(test::UniformCantilever({0, 0, 1}, 1.0, 0.02, 5), wood);
  const FemModel large(test::YTree(), wood);
  ASSERT_NE(small.dof_count(), large.dof_count());
  const ModalBasis modes = ComputeModes(small, {.count = 4});
  const std::string error =
      test::ErrorOf<InputError>([&] { ComputeEffectiveMasses(large, modes); });
  EXPECT_THAT(error, HasSubstr("shapes"));
  EXPECT_THAT(error, HasSubstr("degrees of freedom"));
  EXPECT_EQ(ComputeEffectiveMasses(small, modes).count(), 4);
}

TEST(FemEffectiveMass, LowestSwayModeIsMinusOneWhenNoModeSways) {
  EffectiveMasses masses;
  EXPECT_EQ(LowestSwayMode(masses), -1);  // no modes at all
  masses.horizontal = Eigen::VectorXd{{0.001, 0.05, 0.099}};
  EXPECT_EQ(LowestSwayMode(masses), -1);
  EXPECT_EQ(LowestSwayMode(masses, 0.05), 1);  // the threshold itself counts
  masses.horizontal[2] = kSwayHorizontalFraction;
  EXPECT_EQ(LowestSwayMode(masses), 2);
}

}  // namespace
}  // namespace simtree::synth
