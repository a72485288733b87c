#pragma once
// Small trees with closed-form answers for the FEM oracle's tests.

#include <cmath>
#include <functional>
#include <string>

#include "simtree/core/error.h"
#include "simtree/core/frames.h"
#include "simtree/core/tree.h"
#include "simtree/core/units.h"
#include "simtree/synth/detail/wood.h"
#include "test_util.h"

namespace simtree::test {

// Green wood without damping unless a test asks for it.
inline synth::WoodProperties TestWood() {
  synth::WoodProperties wood;
  wood.youngs_modulus_pa = 8.0e9;
  wood.shear_modulus_pa = 0.5e9;
  wood.density_kg_m3 = 900.0;
  return wood;
}

// One straight branch from `base` along `direction`, `segments` equal segments, radius given as a
// function of the fraction along it.
inline Tree Cantilever(const Eigen::Vector3d& base, const Eigen::Vector3d& direction, double length,
                       int segments, const std::function<double(double)>& radius_at) {
  Tree tree;
  Branch b;
  const Eigen::Vector3d d = direction.normalized();
  for (int i = 0; i <= segments; ++i) {
    const double t = static_cast<double>(i) / segments;
    b.nodes.push_back({base + t * length * d, radius_at(t)});
  }
  tree.branches.push_back(b);
  AssignLevels(tree);
  ComputeFrames(tree);
  return tree;
}

inline Tree UniformCantilever(const Eigen::Vector3d& direction, double length, double radius,
                              int segments = 20) {
  return Cantilever({0.3, -0.2, 0.1}, direction, length, segments,
                    [radius](double) { return radius; });
}

// A Y: a trunk up +Z and two equal children from its top, mirror images under x -> -x, in the
// x-z plane, `angle` from the vertical.
inline Tree YTree(double trunk_radius = 0.08, double child_radius = 0.03, double angle = 0.7) {
  Tree tree;
  Branch trunk;
  for (int i = 0; i <= 10; ++i) trunk.nodes.push_back({{0, 0, 0.1 * i}, trunk_radius});
  tree.branches.push_back(trunk);
  for (double side : {1.0, -1.0}) {
    Branch child;
    child.id = tree.size();
    child.parent = 0;
    child.parent_node = 10;
    const Eigen::Vector3d top(0, 0, 1.0);
    const Eigen::Vector3d d(side * std::sin(angle), 0, std::cos(angle));
    for (int i = 0; i <= 10; ++i) child.nodes.push_back({top + 0.1 * i * d, child_radius});
    tree.branches.push_back(child);
  }
  AssignLevels(tree);
  ComputeFrames(tree);
  return tree;
}

// Closed forms of a uniform Euler-Bernoulli cantilever of solid circular section.
inline double SecondMoment(double r) { return kPi * std::pow(r, 4) / 4.0; }
inline double CantileverFrequencyHz(double beta_l, const synth::WoodProperties& w, double length,
                                    double radius) {
  const double ei = w.youngs_modulus_pa * SecondMoment(radius);
  const double rho_a = w.density_kg_m3 * kPi * radius * radius;
  return beta_l * beta_l / (kTwoPi * length * length) * std::sqrt(ei / rho_a);
}
inline constexpr double kBetaL1 = 1.8751040687;
inline constexpr double kBetaL2 = 4.6940911330;

}  // namespace simtree::test
