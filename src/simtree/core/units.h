#pragma once
// Units and constants. Inside simtree everything is SI (metres, seconds, kilograms) and angles
// are radians; degrees exist only at the edges, in names ending in `_deg`.

#include <limits>
#include <numbers>

namespace simtree {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;
inline constexpr double kGravity = 9.80665;  // m/s^2
// What was not measured or cannot be computed (written as null in simtree's JSON files).
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

constexpr double DegToRad(double deg) { return deg * kPi / 180.0; }
constexpr double RadToDeg(double rad) { return rad * 180.0 / kPi; }

// Stiffness of one modal oscillator of mass m at frequency f: k = 4 m pi^2 f^2 (paper Eq. 6).
constexpr double ModalStiffness(double mass_kg, double frequency_hz) {
  return 4.0 * mass_kg * kPi * kPi * frequency_hz * frequency_hz;
}
// The mass that gives stiffness k at frequency f.
constexpr double ModalMass(double stiffness, double frequency_hz) {
  return stiffness / (4.0 * kPi * kPi * frequency_hz * frequency_hz);
}

}  // namespace simtree
