#pragma once
// Mode shapes of a branch as a cantilever (paper Eq. 5): the first Euler-Bernoulli bending mode of
// a clamped-free beam, and the first torsion mode of a clamped-free shaft, both as functions of the
// normalised arc length x = s / L in [0, 1] and normalised to 1 at the tip. With this
// normalisation a modal coordinate is the tip deflection (metres) or tip twist (radians), and the
// modal mass is the one for which a static tip force F bends the tip by F / k.

namespace simtree::dynamics {

// beta_1 L of the first clamped-free bending mode: cos(b) cosh(b) = -1.
inline constexpr double kCantileverBeta1 = 1.8751040687119611;

// phi(x) = [cosh bx - cos bx - sigma (sinh bx - sin bx)] / (value at x = 1), with
// sigma = (cosh b + cos b) / (sinh b + sin b). phi(0) = phi'(0) = 0, phi(1) = 1, and the free end
// carries no moment or shear (phi''(1) = phi'''(1) = 0). (simready/build.h has the same shape
// as CantileverModeShape for modal masses; these add its derivatives.)
double BendingModeShape(double x);
// d phi / dx (per unit of x: divide by L for the slope per metre).
double BendingModeSlope(double x);
// d^2 phi / dx^2 (curvature per unit x^2), for tests and for strain-like outputs.
double BendingModeCurvature(double x);

// psi(x) = sin(pi x / 2): the twist angle along a clamped-free shaft, 0 at the base, 1 at the tip.
double TwistModeShape(double x);

}  // namespace simtree::dynamics
