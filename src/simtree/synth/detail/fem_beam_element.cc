#include "simtree/synth/detail/fem_beam_element.h"

#include <array>
#include <cmath>

#include <Eigen/Geometry>

#include "simtree/core/units.h"

namespace simtree::synth {
namespace {

// Five-point Gauss-Legendre rule on [0, 1]: exact for polynomials up to degree 9 (the highest
// integrand here is rho A(x) H(x)^2, degree 2 + 6).
struct GaussPoint {
  double xi;
  double weight;
};
constexpr std::array<GaussPoint, 5> kGauss5 = {{
    {0.5 - 0.5 * 0.9061798459386640, 0.5 * 0.2369268850561891},
    {0.5 - 0.5 * 0.5384693101056831, 0.5 * 0.4786286704993665},
    {0.5, 0.5 * 0.5688888888888889},
    {0.5 + 0.5 * 0.5384693101056831, 0.5 * 0.4786286704993665},
    {0.5 + 0.5 * 0.9061798459386640, 0.5 * 0.2369268850561891},
}};

// Section properties of a solid circle of radius r.
struct Section {
  double area;     // pi r^2
  double inertia;  // second moment about a diameter, pi r^4 / 4
  double polar;    // polar moment (torsion constant of a solid circle), pi r^4 / 2
};
Section SectionAt(double r) {
  const double r2 = r * r;
  return {kPi * r2, kPi * r2 * r2 / 4.0, kPi * r2 * r2 / 2.0};
}

// Cubic Hermite functions on x = xi L and their first and second x-derivatives, ordered as the
// coefficients of (v_a, slope_a, v_b, slope_b).
struct Hermite {
  std::array<double, 4> h, d1, d2;
};
Hermite HermiteAt(double xi, double length) {
  const double x2 = xi * xi, x3 = x2 * xi, l = length;
  Hermite out;
  out.h = {1 - 3 * x2 + 2 * x3, l * (xi - 2 * x2 + x3), 3 * x2 - 2 * x3, l * (-x2 + x3)};
  out.d1 = {(-6 * xi + 6 * x2) / l, 1 - 4 * xi + 3 * x2, (6 * xi - 6 * x2) / l, -2 * xi + 3 * x2};
  out.d2 = {(-6 + 12 * xi) / (l * l), (-4 + 6 * xi) / l, (6 - 12 * xi) / (l * l),
            (-2 + 6 * xi) / l};
  return out;
}

// Local degrees of freedom of the bending in the x-y plane (v, theta_z) and in the x-z plane
// (w, theta_y; slope dw/dx = -theta_y, hence the signs).
constexpr std::array<int, 4> kBendY = {1, 5, 7, 11};
constexpr std::array<int, 4> kBendZ = {2, 4, 8, 10};
constexpr std::array<double, 4> kBendZSign = {1, -1, 1, -1};

// Displacement (rows 0-2) and rotation (rows 3-5) of the section at xi, in local coordinates.
PointRows LocalPointRows(double xi, double length) {
  const Hermite hm = HermiteAt(xi, length);
  PointRows n = PointRows::Zero();
  n(0, 0) = 1 - xi;  // axial
  n(0, 6) = xi;
  n(3, 3) = 1 - xi;  // twist
  n(3, 9) = xi;
  for (int k = 0; k < 4; ++k) {
    n(1, kBendY[k]) = hm.h[k];                    // v
    n(5, kBendY[k]) = hm.d1[k];                   // theta_z = dv/dx
    n(2, kBendZ[k]) = kBendZSign[k] * hm.h[k];    // w
    n(4, kBendZ[k]) = -kBendZSign[k] * hm.d1[k];  // theta_y = -dw/dx
  }
  return n;
}

}  // namespace

Eigen::Matrix3d BeamElement::LocalAxes() const {
  const Eigen::Vector3d x = (b - a).normalized();
  const Eigen::Vector3d y = x.unitOrthogonal();
  Eigen::Matrix3d r;
  r.row(0) = x;
  r.row(1) = y;
  r.row(2) = x.cross(y);
  return r;
}

Matrix12d BeamElement::WorldToLocal() const {
  const Eigen::Matrix3d r = LocalAxes();
  Matrix12d t = Matrix12d::Zero();
  for (int k = 0; k < 4; ++k) t.block<3, 3>(3 * k, 3 * k) = r;
  return t;
}

Matrix12d BeamElement::Stiffness(const WoodProperties& wood) const {
  const double l = Length();
  const double e = wood.youngs_modulus_pa, g = wood.shear_modulus_pa;
  Matrix12d k = Matrix12d::Zero();
  // Stretch and twist: the exact stiffness of a tapered bar, one over its flexibility
  // integral_0^L dx / EA(x) (and / GJ(x)), in closed form for a linear radius. (Linear shape
  // functions would give the mean of EA instead, an O(h^2) error that shows wherever a curved
  // branch bends out of its plane and twists.)
  // Young wood's lower modulus (wood.h): at the mid radius for stretch and twist (elements are a
  // few cm long), at each Gauss point's radius for bending.
  const double ra = radius_a, rb = radius_b;
  const double mid_factor = wood.StiffnessFactorAt(0.5 * (ra + rb));
  const double axial = mid_factor * e * kPi * ra * rb / l;
  const double twist =
      mid_factor * g * kPi / 2.0 * 3.0 * std::pow(ra * rb, 3) / (l * (ra * ra + ra * rb + rb * rb));
  for (int i : {0, 6}) {
    for (int j : {0, 6}) k(i, j) = (i == j ? 1 : -1) * axial;
  }
  for (int i : {3, 9}) {
    for (int j : {3, 9}) k(i, j) = (i == j ? 1 : -1) * twist;
  }
  for (const GaussPoint& q : kGauss5) {
    const double radius = (1 - q.xi) * radius_a + q.xi * radius_b;
    const Section s = SectionAt(radius);
    const double w = q.weight * l;
    const Hermite hm = HermiteAt(q.xi, l);
    const double bend = w * e * wood.StiffnessFactorAt(radius) * s.inertia;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        const double c = bend * hm.d2[i] * hm.d2[j];
        k(kBendY[i], kBendY[j]) += c;
        k(kBendZ[i], kBendZ[j]) += kBendZSign[i] * kBendZSign[j] * c;
      }
    }
  }
  const Matrix12d t = WorldToLocal();
  return t.transpose() * k * t;
}

Matrix12d BeamElement::Mass(const WoodProperties& wood) const {
  const double l = Length();
  const double rho = wood.density_kg_m3;
  Matrix12d m = Matrix12d::Zero();
  for (const GaussPoint& q : kGauss5) {
    const Section s = SectionAt((1 - q.xi) * radius_a + q.xi * radius_b);
    const PointRows n = LocalPointRows(q.xi, l);
    // Mass per length for the three translations, polar and diametral mass moments per length
    // for the three rotations (twist, then the two bending slopes: rotary inertia).
    Eigen::Matrix<double, 6, 1> density;
    density << s.area, s.area, s.area, s.polar, s.inertia, s.inertia;
    density *= rho * q.weight * l;
    m.noalias() += n.transpose() * density.asDiagonal() * n;
  }
  const Matrix12d t = WorldToLocal();
  return t.transpose() * m * t;
}

Vector12d BeamElement::Weight(const WoodProperties& wood, const Eigen::Vector3d& gravity) const {
  const double l = Length();
  const Eigen::Vector3d g_local = LocalAxes() * gravity;
  Vector12d f = Vector12d::Zero();
  for (const GaussPoint& q : kGauss5) {
    const Section s = SectionAt((1 - q.xi) * radius_a + q.xi * radius_b);
    const PointRows n = LocalPointRows(q.xi, l);
    f.noalias() +=
        n.topRows<3>().transpose() * (wood.density_kg_m3 * s.area * q.weight * l * g_local);
  }
  return WorldToLocal().transpose() * f;
}

PointRows BeamElement::PointOperator(double xi) const {
  const Eigen::Matrix3d r = LocalAxes();
  const PointRows n = LocalPointRows(xi, Length());
  PointRows out;
  // world = R^T local on both the output (displacement, rotation) and every node block of input.
  for (int row = 0; row < 2; ++row) {
    for (int col = 0; col < 4; ++col) {
      out.block<3, 3>(3 * row, 3 * col) = r.transpose() * n.block<3, 3>(3 * row, 3 * col) * r;
    }
  }
  return out;
}

}  // namespace simtree::synth
