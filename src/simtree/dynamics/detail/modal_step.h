#pragma once
// Advancing the branches' modal oscillators over a step (paper Eq. 6): a branch's primary motion
// under its external loads, and its children's swings under its motion.

#include <array>
#include <span>

#include "simtree/dynamics/detail/branch_model.h"
#include "simtree/dynamics/detail/branch_state.h"
#include "simtree/dynamics/detail/loads.h"

namespace simtree::dynamics {

// The three oscillator steps of a branch for a step of dt seconds.
std::array<OscillatorStep, 3> MakeBranchSteps(const BranchMechanics& mechanics, double dt,
                                              Integrator integrator);

// The share of a branch's swing bank kept over a step of dt (BranchLink::bank_keep).
double SwingBankKeep(const BranchMechanics& mechanics, double dt);

// The static deflection of the three modes under generalised forces `force`: q = F / (m w^2).
std::array<double, 3> StaticDeflection(const BranchMechanics& mechanics,
                                       const std::array<double, 3>& force);

// Modal energy of a state, kinetic plus elastic (J).
double ModalEnergy(const BranchMechanics& mechanics, const ModalState& state);

// Advances a branch with no parent (a trunk) by dt under the generalised forces `force` (N, N,
// N m) on its modes, first setting its swing budget for its children (BranchState).
void AdvanceRoot(const BranchLink& link, const std::array<double, 3>& force, double dt,
                 BranchState& state);

// Advances the children of branch `parent`, which has been advanced and posed for this step (the
// children's poses are still the last step's): each child's primary motion under its
// generalised forces (`loads[child].q`; `loads` empty: none), its swing budget for its own
// children, and, with `base_excitation`, its swing under the acceleration of its base.
//
// The motion of a branch is the sum of two responses of its three oscillators: the primary one to
// its external load, and the swing under the inertial load of its base's acceleration. Only the
// ancestors' primary motion drives a swing: swings do not drive further swings (a one-way cascade
// through six levels of equal frequency amplifies a pull 250,000-fold).
//
// The coupling runs one way, parent to child, so that every branch keeps its measured frequency
// and damping; but a one-way drive has no energy limit. A child tuned to its parent (the usual
// case: a pull test measures the tree's modes, so a branch and its parent swing at the same
// frequency, and an unmeasured branch takes its ancestor's) rings up for as long as its parent
// swings and holds many times the energy the tree was let go with (18 times on the quick
// synthetic capture's simulation-ready tree, its nodes swinging 3.8 m on a 3.7 m tree). So the
// swings are paid for: the energy the drive puts into a family's swings over a step (its exact
// work on the children's oscillators, about their equilibria under their loads) is drawn from
// what the parent's own damping takes out of its motion over that step and has taken before (its
// bank, fading as the parent's motion does); when the drive asks for more, the family's drive is
// scaled down until it fits. A
// measured damping ratio is all the energy a branch's motion loses, to the air, to the wood and
// to the children it shakes: their swings take their share of it, and the tree's energy never
// grows without a load. A light child takes little of its parent's losses and swings as under
// the free one-way drive; a heavy child tuned to its parent no longer rings up on energy that
// does not exist.
void AdvanceChildren(int parent, std::span<const int> children, std::span<const BranchLink> links,
                     std::span<const Load> loads, double dt, bool base_excitation,
                     std::span<BranchState> states);

}  // namespace simtree::dynamics
