#include "simtree/synth/detail/wood.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "simtree/core/error.h"

namespace simtree::synth {
namespace {

TEST(Wood, RayleighCoefficientsHitBothAnchors) {
  WoodProperties wood;
  wood.SetRayleighFromRatios(1.0, 0.04, 8.0, 0.03);
  EXPECT_NEAR(wood.DampingRatioAt(1.0), 0.04, 1e-12);
  EXPECT_NEAR(wood.DampingRatioAt(8.0), 0.03, 1e-12);
  EXPECT_GT(wood.rayleigh_alpha, 0.0);
  EXPECT_GT(wood.rayleigh_beta, 0.0);
  // Mass-proportional damping falls with frequency, stiffness-proportional damping grows.
  EXPECT_LT(wood.DampingRatioAt(3.0), 0.04);
  EXPECT_GT(wood.DampingRatioAt(40.0), 0.03);
}

TEST(Wood, ImpossibleRayleighPairIsRefused) {
  WoodProperties wood;
  // Damping that grows faster than f between the anchors needs alpha < 0.
  EXPECT_THROW(wood.SetRayleighFromRatios(1.0, 0.01, 2.0, 0.05), InputError);
  EXPECT_THROW(wood.SetRayleighFromRatios(1.0, 0.01, 1.0, 0.05), InputError);
}

TEST(Wood, YoungWoodIsLessStiffBelowTheMatureRadius) {
  WoodProperties wood;
  EXPECT_EQ(wood.StiffnessFactorAt(0.001), 1.0);  // exponent 0: one modulus
  wood.mature_radius_m = 0.04;
  wood.young_wood_exponent = 0.5;
  EXPECT_NEAR(wood.StiffnessFactorAt(0.01), 0.5, 1e-12);
  EXPECT_EQ(wood.StiffnessFactorAt(0.04), 1.0);
  EXPECT_EQ(wood.StiffnessFactorAt(0.2), 1.0);
  EXPECT_EQ(wood.StiffnessFactorAt(0.0), 0.0);
}

TEST(Wood, ValidationNamesTheField) {
  WoodProperties wood;
  wood.density_kg_m3 = std::numeric_limits<double>::quiet_NaN();
  try {
    ValidateWood(wood, "preset.json");
    FAIL() << "NaN density accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("density_kg_m3"), std::string::npos) << e.what();
  }
  wood = WoodProperties{};
  wood.youngs_modulus_pa = -1;
  EXPECT_THROW(ValidateWood(wood, "x"), InputError);
  wood = WoodProperties{};
  wood.young_wood_exponent = -0.5;
  EXPECT_THROW(ValidateWood(wood, "x"), InputError);
  wood = WoodProperties{};
  wood.mature_radius_m = 0.0;
  EXPECT_THROW(ValidateWood(wood, "x"), InputError);
  EXPECT_NO_THROW(ValidateWood(WoodProperties{}, "x"));
}

}  // namespace
}  // namespace simtree::synth
