#include "simtree/dynamics/detail/mode_shapes.h"

#include <algorithm>
#include <cmath>

#include "simtree/core/units.h"

namespace simtree::dynamics {
namespace {

constexpr double kBeta = kCantileverBeta1;

double Sigma() {
  static const double sigma =
      (std::cosh(kBeta) + std::cos(kBeta)) / (std::sinh(kBeta) + std::sin(kBeta));
  return sigma;
}

double RawShape(double x) {
  const double bx = kBeta * x;
  return std::cosh(bx) - std::cos(bx) - Sigma() * (std::sinh(bx) - std::sin(bx));
}

double TipValue() {
  static const double tip = RawShape(1.0);
  return tip;
}

}  // namespace

double BendingModeShape(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return RawShape(x) / TipValue();
}

double BendingModeSlope(double x) {
  x = std::clamp(x, 0.0, 1.0);
  const double bx = kBeta * x;
  return kBeta * (std::sinh(bx) + std::sin(bx) - Sigma() * (std::cosh(bx) - std::cos(bx))) /
         TipValue();
}

double BendingModeCurvature(double x) {
  x = std::clamp(x, 0.0, 1.0);
  const double bx = kBeta * x;
  return kBeta * kBeta * (std::cosh(bx) + std::cos(bx) - Sigma() * (std::sinh(bx) + std::sin(bx))) /
         TipValue();
}

double TwistModeShape(double x) { return std::sin(0.5 * kPi * std::clamp(x, 0.0, 1.0)); }

}  // namespace simtree::dynamics
