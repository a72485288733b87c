#pragma once
// Wood as the FEM oracle sees it: one linear-elastic, isotropic-in-section material per tree
// (green wood along the grain), and Rayleigh damping C = alpha M + beta K (paper Eq. 4).
//
// Green (freshly cut, water-saturated) values, not the kiln-dried ones of timber tables: a
// living branch is wet. The shear modulus is the longitudinal-tangential one, about E / 16 for
// hardwoods; it only matters for twist.

#include <string>
#include <utility>

namespace simtree::synth {

struct WoodProperties {
  double youngs_modulus_pa = 8.0e9;
  double shear_modulus_pa = 0.5e9;
  double density_kg_m3 = 900.0;
  // Young wood is less stiff than mature wood (juvenile wood: low density, a large microfibril
  // angle): E and G above are the mature stem's, and below mature_radius_m both fall as
  // (r / mature_radius_m)^young_wood_exponent. An exponent of 0: one modulus for every radius.
  double mature_radius_m = 0.02;
  double young_wood_exponent = 0.0;
  // Rayleigh coefficients: the modal damping ratio at frequency f is
  //   zeta(f) = alpha / (4 pi f) + beta pi f.
  double rayleigh_alpha = 0.0;  // 1/s
  double rayleigh_beta = 0.0;   // s

  double DampingRatioAt(double frequency_hz) const;
  // The factor on E and G of wood at this radius (1 at and above mature_radius_m).
  double StiffnessFactorAt(double radius_m) const;
  // Sets alpha and beta so that zeta(f1) = zeta1 and zeta(f2) = zeta2 (f1 != f2). Throws
  // InputError when the pair needs a negative coefficient.
  void SetRayleighFromRatios(double f1_hz, double zeta1, double f2_hz, double zeta2);
};

// Throws InputError naming `source` and the field when a value is not finite or not positive
// (the Rayleigh coefficients and young_wood_exponent may be zero).
void ValidateWood(const WoodProperties& wood, const std::string& source);

}  // namespace simtree::synth
