#include "simtree/dynamics/detail/mode_shapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace simtree::dynamics {
namespace {

double NumericDerivative(double (*f)(double), double x, double h = 1e-5) {
  return (f(x + h) - f(x - h)) / (2 * h);
}

TEST(ModeShapes, CantileverClampedAtTheBaseNormalisedAtTheTip) {
  EXPECT_NEAR(BendingModeShape(0.0), 0.0, 1e-14);
  EXPECT_NEAR(BendingModeSlope(0.0), 0.0, 1e-14);
  EXPECT_NEAR(BendingModeShape(1.0), 1.0, 1e-14);
  // Monotone from base to tip.
  for (double x = 0.01; x <= 1.0; x += 0.01) {
    EXPECT_GT(BendingModeShape(x), BendingModeShape(x - 0.01));
  }
}

TEST(ModeShapes, CantileverFreeEndCarriesNoMomentNorShear) {
  EXPECT_NEAR(BendingModeCurvature(1.0), 0.0, 1e-9);
  const double third = (BendingModeCurvature(1.0) - BendingModeCurvature(1.0 - 1e-5)) / 1e-5;
  EXPECT_NEAR(third, 0.0, 1e-3);
}

TEST(ModeShapes, CantileverSatisfiesTheBeamEquation) {
  // phi'''' = beta^4 phi: check with finite differences of the curvature.
  for (double x : {0.2, 0.5, 0.8}) {
    const double h = 1e-3;
    const double fourth =
        (BendingModeCurvature(x + h) - 2 * BendingModeCurvature(x) + BendingModeCurvature(x - h)) /
        (h * h);
    EXPECT_NEAR(fourth, std::pow(kCantileverBeta1, 4) * BendingModeShape(x), 1e-4) << x;
  }
  // Slope and curvature are the derivatives of the shape.
  for (double x : {0.1, 0.4, 0.9}) {
    EXPECT_NEAR(BendingModeSlope(x), NumericDerivative(BendingModeShape, x), 1e-8);
    EXPECT_NEAR(BendingModeCurvature(x), NumericDerivative(BendingModeSlope, x), 1e-8);
  }
  // The known tip slope of the tip-normalised first mode.
  EXPECT_NEAR(BendingModeSlope(1.0), 1.37650, 1e-4);
}

TEST(ModeShapes, TwistGrowsAlongTheBranch) {
  EXPECT_NEAR(TwistModeShape(0.0), 0.0, 1e-15);
  EXPECT_NEAR(TwistModeShape(1.0), 1.0, 1e-15);
  EXPECT_GT(TwistModeShape(0.5), TwistModeShape(0.25));
  // Clamped outside [0, 1].
  EXPECT_EQ(TwistModeShape(2.0), 1.0);
  EXPECT_EQ(BendingModeShape(-1.0), 0.0);
}

}  // namespace
}  // namespace simtree::dynamics
