#pragma once
// One modal oscillator of paper Eq. 6, q'' + 2 zeta w q' + w^2 q = g (g = generalised force / modal
// mass, w = 2 pi f), advanced over a time step by a 2x2 linear map:
//   [q; v] <- [a11 a12; a21 a22] [q; v] + [b1; b2] g
// Every integrator below has that form, so one code path runs them all and only the coefficients
// differ.
//
// kExact (the default) is the exact solution over the step for a force held constant over it
// (zero-order hold): the matrix exponential of the oscillator. It is unconditionally stable for any
// frequency, damping (under-, critically or over-damped) and step; its free decay has the exact
// frequency and envelope at any step, and its energy never grows without a force.
// kSemiImplicitEuler is the update of the authors' released demo (v += dt a; q += dt v): stable
// only while w dt < 2 (for light damping). kExplicitEuler is the classical Euler method the paper
// names: its energy grows by (1 + w^2 dt^2) per step when undamped, so it diverges for any step
// unless damping outweighs it. Both are kept for comparison.

#include <string>

namespace simtree::dynamics {

enum class Integrator { kExact, kSemiImplicitEuler, kExplicitEuler };

const char* ToString(Integrator integrator);
// "exact", "semi-implicit-euler", "explicit-euler"; throws InputError naming `where` otherwise.
Integrator ParseIntegrator(const std::string& name, const std::string& where = "integrator");

struct OscillatorStep {
  double a11 = 1, a12 = 0, a21 = 0, a22 = 1;
  double b1 = 0, b2 = 0;

  // Advances (q, v) by one step under the acceleration g = force / modal mass.
  void Apply(double g, double& q, double& v) const {
    const double q1 = a11 * q + a12 * v + b1 * g;
    const double v1 = a21 * q + a22 * v + b2 * g;
    q = q1;
    v = v1;
  }
};

// Coefficients for frequency f > 0 (Hz), damping ratio zeta >= 0 and step dt > 0 (s).
OscillatorStep MakeOscillatorStep(double frequency_hz, double damping_ratio, double dt,
                                  Integrator integrator);

// Energy of one oscillator of modal mass m: kinetic 1/2 m v^2 plus elastic 1/2 m w^2 q^2.
double OscillatorEnergy(double modal_mass, double frequency_hz, double q, double v);

}  // namespace simtree::dynamics
