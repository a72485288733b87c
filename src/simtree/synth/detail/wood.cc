#include "simtree/synth/detail/wood.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "simtree/core/error.h"

namespace simtree::synth {

double WoodProperties::DampingRatioAt(double frequency_hz) const {
  const double pi = std::numbers::pi;
  return rayleigh_alpha / (4.0 * pi * frequency_hz) + rayleigh_beta * pi * frequency_hz;
}

double WoodProperties::StiffnessFactorAt(double radius_m) const {
  if (young_wood_exponent == 0.0 || radius_m >= mature_radius_m) return 1.0;
  return std::pow(std::max(radius_m, 0.0) / mature_radius_m, young_wood_exponent);
}

void WoodProperties::SetRayleighFromRatios(double f1_hz, double zeta1, double f2_hz, double zeta2) {
  // zeta(f) = a / (4 pi f) + b pi f, two equations in (a, b).
  const double pi = std::numbers::pi;
  if (!(f1_hz > 0 && f2_hz > 0) || f1_hz == f2_hz) {
    throw InputError("wood", "rayleigh", "expected two different positive frequencies");
  }
  const double a11 = 1.0 / (4.0 * pi * f1_hz), a12 = pi * f1_hz;
  const double a21 = 1.0 / (4.0 * pi * f2_hz), a22 = pi * f2_hz;
  const double det = a11 * a22 - a12 * a21;
  const double alpha = (zeta1 * a22 - a12 * zeta2) / det;
  const double beta = (a11 * zeta2 - zeta1 * a21) / det;
  if (alpha < 0 || beta < 0) {
    throw InputError("wood", "rayleigh",
                     "damping ratios " + std::to_string(zeta1) + " at " + std::to_string(f1_hz) +
                         " Hz and " + std::to_string(zeta2) + " at " + std::to_string(f2_hz) +
                         " Hz need a negative Rayleigh coefficient");
  }
  rayleigh_alpha = alpha;
  rayleigh_beta = beta;
}

void ValidateWood(const WoodProperties& wood, const std::string& source) {
  auto positive = [&](double value, const char* field) {
    if (!std::isfinite(value) || value <= 0) {
      throw InputError(source, field, "expected a positive number, got " + std::to_string(value));
    }
  };
  positive(wood.youngs_modulus_pa, "youngs_modulus_pa");
  positive(wood.shear_modulus_pa, "shear_modulus_pa");
  positive(wood.density_kg_m3, "density_kg_m3");
  positive(wood.mature_radius_m, "mature_radius_m");
  auto non_negative = [&](double value, const char* field) {
    if (!std::isfinite(value) || value < 0) {
      throw InputError(source, field,
                       "expected a non-negative number, got " + std::to_string(value));
    }
  };
  non_negative(wood.rayleigh_alpha, "rayleigh_alpha");
  non_negative(wood.rayleigh_beta, "rayleigh_beta");
  non_negative(wood.young_wood_exponent, "young_wood_exponent");
}

}  // namespace simtree::synth
