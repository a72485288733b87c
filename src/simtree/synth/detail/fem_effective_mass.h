#pragma once
// Effective modal masses of the FEM oracle's modes: how much of the tree each mode carries when
// the ground moves the whole tree rigidly, which tells a sway mode from a torsional one.
//
// For a unit rigid-body motion r of the base (a vector over the free degrees of freedom: what
// every node does when the tree moves with its clamp as one rigid body), mode i's participation
// factor is G_i = phi_i^T M r / phi_i^T M phi_i and its effective mass G_i^2 phi_i^T M phi_i
// (standard structural dynamics; e.g. Chopra, Dynamics of Structures, ch. 13). Over a complete
// basis the effective masses add up to r^T M r, the mass (or moment of inertia) that moves with
// the base; each mode's share of it is a fraction in [0, 1]. Three base motions:
//   - x, y: translation along the world axes (every node moves by the unit vector, no rotation);
//     r^T M r is the mass of the free nodes, the same for both.
//   - torsion: rotation about the vertical through the trunk base (FEM node 0): a node at p moves
//     by e_z x (p - base) and turns by e_z; r^T M r is the polar moment of inertia about it.
// A mode's horizontal fraction is (G_x^2 + G_y^2) / m: its share of one horizontal direction's
// mass, summed over both so that it does not depend on how the eigensolver orients the two modes
// of an equal-frequency pair (so over a complete basis the horizontal fractions add up to 2).
//
// A uniform vertical cantilever: each mode of the first bending pair carries 61.3% of the mass
// in its plane (the classic first-mode value), no torsion; the first torsional mode carries
// 8 / pi^2 = 81.1% of the polar moment (a fixed-free shaft, sin(pi s / 2L)) and no horizontal
// mass.
// A sway mode of a tree moves its crown sideways (a large horizontal fraction); a torsional mode
// turns the crown about the trunk (a large torsion fraction, little horizontal).

#include <Eigen/Core>

#include "simtree/synth/detail/fem_model.h"
#include "simtree/synth/detail/fem_modes.h"

namespace simtree::synth {

struct EffectiveMasses {
  // Per mode (the basis' order): fractions of the base motion's mass, each in [0, 1].
  Eigen::VectorXd x, y, torsion;
  Eigen::VectorXd horizontal;  // x + y
  // r^T M r of the base motions: the free nodes' mass (kg, either horizontal direction) and the
  // polar moment of inertia about the vertical through the trunk base (kg m^2).
  double translating_mass_kg = 0.0;
  double polar_moment_kg_m2 = 0.0;

  int count() const { return static_cast<int>(horizontal.size()); }
};

// Throws InputError when `modes` are not the modes of `model` (row count).
EffectiveMasses ComputeEffectiveMasses(const FemModel& model, const ModalBasis& modes);

// The horizontal fraction from which a mode counts as a sway mode. Measured on the presets' trees
// (acer_palmatum, acer_rubrum and magnolia, seeds 1-5, 100 modes each): the lowest sway mode
// carries 16-67% of the horizontal mass; acer_palmatum's first mode is a crown torsion (83-95% of
// the polar moment, 0.6-5.5% horizontal), so its lowest sway mode is its second. A torsional mode
// may still pass the threshold (acer_rubrum seed 2's third mode: 65% torsion, 17% horizontal).
inline constexpr double kSwayHorizontalFraction = 0.1;

// The lowest mode whose horizontal fraction is at least `min_horizontal_fraction`; -1 when none.
int LowestSwayMode(const EffectiveMasses& masses,
                   double min_horizontal_fraction = kSwayHorizontalFraction);

}  // namespace simtree::synth
