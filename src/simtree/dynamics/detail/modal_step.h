#pragma once
// Advancing one branch's three modal oscillators over a step (paper Eq. 6).

#include <array>

#include "simtree/dynamics/detail/branch_model.h"
#include "simtree/dynamics/detail/branch_state.h"

namespace simtree::dynamics {

// The three oscillator steps of a branch for a step of dt seconds.
std::array<OscillatorStep, 3> MakeBranchSteps(const BranchMechanics& mechanics, double dt,
                                              Integrator integrator);

// The static deflection of the three modes under generalised forces `force`: q = F / (m w^2).
std::array<double, 3> StaticDeflection(const BranchMechanics& mechanics,
                                       const std::array<double, 3>& force);

// Advances `state` by dt under the generalised forces `force` (N, N, N m) on its modes and, with
// `base_excitation`, the acceleration of its base on `parent` (null for the trunk), which must
// have been advanced and posed for this step already; `state`'s pose is still the last step's.
//
// The motion is the sum of two responses of the same three oscillators: the primary one to the
// external load, and the swing under the inertial load of the base's acceleration. Only the
// ancestors' primary motion drives a swing: swings do not drive further swings. A one-way cascade
// has no physical limit (through six levels of equal frequency it amplifies a pull 250,000-fold);
// in a real tree the children's reactions on their parents stop it, and this keeps every branch
// within one level of resonance of a load.
void AdvanceBranch(const BranchLink& link, const BranchState* parent,
                   const std::array<double, 3>& force, double dt, bool base_excitation,
                   BranchState& state);

}  // namespace simtree::dynamics
