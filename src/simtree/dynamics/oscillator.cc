#include "simtree/dynamics/oscillator.h"

#include <cmath>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/units.h"

namespace simtree::dynamics {
namespace {

// The exact state transition of q'' + 2 zeta w q' + w^2 q = 0 over dt, written with
//   C = cos(wd dt), S = sin(wd dt) / wd     (under-damped, wd^2 = w^2 (1 - zeta^2) > 0)
//   C = cosh(g dt), S = sinh(g dt) / g      (over-damped, g^2 = -wd^2)
// so that Phi = e^(-zeta w dt) [[C + zeta w S, S], [-w^2 S, C - zeta w S]] for every zeta, with the
// exponential folded into cosh/sinh so nothing overflows for long steps.
struct Transition {
  double e_c = 1;  // e^(-zeta w dt) C
  double e_s = 0;  // e^(-zeta w dt) S
};

Transition ExactTransition(double w, double zeta, double dt) {
  const double decay = zeta * w;
  const double mu = w * w * (1.0 - zeta * zeta);  // wd^2, negative when over-damped
  const double x = mu * dt * dt;
  Transition t;
  if (std::abs(x) < 1e-4) {
    // Near critical damping: Taylor series of C and S in mu (error below 1e-14 relative).
    const double e = std::exp(-decay * dt);
    t.e_c = e * (1.0 - x / 2.0 + x * x / 24.0);
    t.e_s = e * dt * (1.0 - x / 6.0 + x * x / 120.0);
  } else if (mu > 0.0) {
    const double wd = std::sqrt(mu);
    const double e = std::exp(-decay * dt);
    t.e_c = e * std::cos(wd * dt);
    t.e_s = e * std::sin(wd * dt) / wd;
  } else {
    const double g = std::sqrt(-mu);  // g < decay, so both exponents below are negative
    const double plus = std::exp((g - decay) * dt);
    const double minus = std::exp((-g - decay) * dt);
    t.e_c = 0.5 * (plus + minus);
    t.e_s = 0.5 * (plus - minus) / g;
  }
  return t;
}

}  // namespace

const char* ToString(Integrator integrator) {
  switch (integrator) {
    case Integrator::kExact:
      return "exact";
    case Integrator::kSemiImplicitEuler:
      return "semi-implicit-euler";
    case Integrator::kExplicitEuler:
      return "explicit-euler";
  }
  return "?";
}

Integrator ParseIntegrator(const std::string& name, const std::string& where) {
  for (Integrator i :
       {Integrator::kExact, Integrator::kSemiImplicitEuler, Integrator::kExplicitEuler}) {
    if (name == ToString(i)) return i;
  }
  throw InputError("", where,
                   fmt::format("expected \"exact\", \"semi-implicit-euler\" or \"explicit-euler\", "
                               "got \"{}\"",
                               name));
}

OscillatorStep MakeOscillatorStep(double frequency_hz, double damping_ratio, double dt,
                                  Integrator integrator) {
  if (!(frequency_hz > 0.0) || !std::isfinite(frequency_hz)) {
    throw InputError("", "frequency_hz",
                     fmt::format("expected a positive finite frequency, got {}", frequency_hz));
  }
  if (!(damping_ratio >= 0.0) || !std::isfinite(damping_ratio)) {
    throw InputError("", "damping_ratio",
                     fmt::format("expected a finite damping ratio >= 0, got {}", damping_ratio));
  }
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    throw InputError("", "time step", fmt::format("expected a positive finite step, got {}", dt));
  }
  const double w = kTwoPi * frequency_hz;
  const double c = 2.0 * damping_ratio * w;  // damping per unit mass
  OscillatorStep s;
  switch (integrator) {
    case Integrator::kExact: {
      const Transition t = ExactTransition(w, damping_ratio, dt);
      const double decay = damping_ratio * w;
      s.a11 = t.e_c + decay * t.e_s;
      s.a12 = t.e_s;
      s.a21 = -w * w * t.e_s;
      s.a22 = t.e_c - decay * t.e_s;
      // Under a constant g the motion relaxes towards the static q = g / w^2 with the same
      // transition: q1 - q* = a11 (q - q*) + a12 v, v1 = a21 (q - q*) + a22 v.
      s.b1 = (1.0 - s.a11) / (w * w);
      s.b2 = -s.a21 / (w * w);
      break;
    }
    case Integrator::kSemiImplicitEuler:
      // v1 = v + dt (g - c v - w^2 q); q1 = q + dt v1.
      s.a21 = -w * w * dt;
      s.a22 = 1.0 - c * dt;
      s.b2 = dt;
      s.a11 = 1.0 + dt * s.a21;
      s.a12 = dt * s.a22;
      s.b1 = dt * dt;
      break;
    case Integrator::kExplicitEuler:
      // q1 = q + dt v; v1 = v + dt (g - c v - w^2 q).
      s.a11 = 1.0;
      s.a12 = dt;
      s.a21 = -w * w * dt;
      s.a22 = 1.0 - c * dt;
      s.b1 = 0.0;
      s.b2 = dt;
      break;
  }
  return s;
}

double OscillatorEnergy(double modal_mass, double frequency_hz, double q, double v) {
  const double w = kTwoPi * frequency_hz;
  return 0.5 * modal_mass * (v * v + w * w * q * q);
}

}  // namespace simtree::dynamics
