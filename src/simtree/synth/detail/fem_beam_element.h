#pragma once
// One 3D Euler-Bernoulli frame element of the FEM oracle: a straight, linearly tapered beam of
// solid circular section between two nodes, 6 degrees of freedom per node.
//
// Local frame: x along the element (node a to node b), y and z across it (any right-handed pair:
// the section is round, so the matrices do not depend on their choice). Local degrees of freedom,
// node a then node b: (u_x, u_y, u_z, theta_x, theta_y, theta_z). Axial and twist motion use
// linear shape functions, bending the cubic Hermite ones (v along y with slope theta_z, w along z
// with slope -theta_y).
//
// The taper is integrated, not averaged: the radius varies linearly along the element, so the
// section properties A = pi r^2, I = pi r^4 / 4, J = pi r^4 / 2 are polynomials of degree 2 and 4,
// and five-point Gauss-Legendre quadrature integrates every bending, mass (translation and rotary
// inertia) and weight term exactly. Stretch and twist take the tapered bar's exact stiffness
// (one over integral dx / EA, dx / GJ, in closed form): the mean section that linear shape
// functions give converges only as h^2, and a curved branch bending out of its plane twists.

#include <Eigen/Core>

#include "simtree/synth/detail/wood.h"

namespace simtree::synth {

using Matrix12d = Eigen::Matrix<double, 12, 12>;
using Vector12d = Eigen::Matrix<double, 12, 1>;
// Rows 0-2: displacement, rows 3-5: small rotation of the section at a point of the element.
using PointRows = Eigen::Matrix<double, 6, 12>;

struct BeamElement {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();  // node positions (world, metres)
  Eigen::Vector3d b = Eigen::Vector3d::UnitX();
  double radius_a = 0.0;  // section radius at each node (metres)
  double radius_b = 0.0;

  double Length() const { return (b - a).norm(); }
  // Rows: the local x, y, z axes in world coordinates (so local = R * world).
  Eigen::Matrix3d LocalAxes() const;
  // The 12 x 12 rotation taking world degrees of freedom to local ones (four copies of R).
  Matrix12d WorldToLocal() const;

  // Element matrices in world coordinates.
  Matrix12d Stiffness(const WoodProperties& wood) const;
  Matrix12d Mass(const WoodProperties& wood) const;
  // Consistent nodal loads (world) of the element's own weight under acceleration `gravity`.
  Vector12d Weight(const WoodProperties& wood, const Eigen::Vector3d& gravity) const;
  // Displacement and rotation (world) at fraction `xi` in [0, 1] of the element, from its 12
  // world degrees of freedom. The transpose maps a point force and moment to consistent nodal
  // loads (the virtual-work equivalent).
  PointRows PointOperator(double xi) const;
};

}  // namespace simtree::synth
