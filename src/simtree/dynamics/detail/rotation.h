#pragma once
// Rotations of the modal model: Rodrigues' formula from a rotation vector, with series for the
// small angles modal rotations have, so the hot paths make no libm call and never divide by zero.

#include <cmath>

#include <Eigen/Core>

namespace simtree::dynamics {

// sin x / x and (1 - cos x) / x^2 from x^2, by their Taylor series for |x| <= 0.5 (error below
// 1e-12), libm beyond.
[[gnu::always_inline]] inline void RotationCoefficients(double angle2, double* sinc, double* cosc) {
  const double a2 = angle2;
  if (a2 < 0.25) {
    // Multiplications by reciprocals: a division costs as much as this whole polynomial.
    constexpr double k6 = 1.0 / 6, k20 = 1.0 / 20, k42 = 1.0 / 42, k72 = 1.0 / 72;
    constexpr double k12 = 1.0 / 12, k30 = 1.0 / 30, k56 = 1.0 / 56, k90 = 1.0 / 90;
    *sinc = 1.0 - a2 * k6 * (1.0 - a2 * k20 * (1.0 - a2 * k42 * (1.0 - a2 * k72)));
    *cosc = 0.5 * (1.0 - a2 * k12 * (1.0 - a2 * k30 * (1.0 - a2 * k56 * (1.0 - a2 * k90))));
  } else {
    const double angle = std::sqrt(a2);
    *sinc = std::sin(angle) / angle;
    *cosc = (1.0 - std::cos(angle)) / a2;
  }
}

// sin and cos of an angle, by series for |x| <= 0.5.
[[gnu::always_inline]] inline void SinCos(double x, double* s, double* c) {
  double sinc = 0, cosc = 0;
  RotationCoefficients(x * x, &sinc, &cosc);
  *s = x * sinc;
  *c = 1.0 - x * x * cosc;
}

// The rotation by the rotation vector w (axis w / |w|, angle |w|): I + sinc K + cosc K^2 with
// K = [w]x and K^2 = w w^T - |w|^2 I, written out.
[[gnu::always_inline]] inline Eigen::Matrix3d RotationFromVector(const Eigen::Vector3d& w) {
  const double x = w.x(), y = w.y(), z = w.z();
  const double a2 = x * x + y * y + z * z;
  double s = 0, c = 0;
  RotationCoefficients(a2, &s, &c);
  Eigen::Matrix3d r;
  r << 1 + c * (x * x - a2), -s * z + c * x * y, s * y + c * x * z,  //
      s * z + c * x * y, 1 + c * (y * y - a2), -s * x + c * y * z,   //
      -s * y + c * x * z, s * x + c * y * z, 1 + c * (z * z - a2);
  return r;
}

}  // namespace simtree::dynamics
