#pragma once
// The whole tree's coupled tuning (robot_calibration.h). The chains are first calibrated one by
// one with their parents held still and their sub-trees rigid, but in the free tree a branch
// swings its children and they swing it back, and gravity acts as a spring too, which moves its
// ringing (tree01: +25% on a first-level branch). This tunes on the whole tree's linearisation
// (detail/joint_space_model.h):
//  1. the generalised eigenproblem (diag(k) + G) phi = lambda M phi;
//  2. every branch and bending plane (a "group": that branch's hinges of that kind) gets one mode
//     of its own, the one whose strain energy lies most in the group's springs per unit
//     eigenvalue (so a chain's fundamental before its higher modes), one group to one mode,
//     greedily from the strongest claim;
//  3. a Newton step on the groups' log-stiffness scales: d log lambda_m / d log s_h is group h's
//     share of mode m's strain energy, so J delta = log(omega_target^2 / lambda_assigned);
//  4. damping stays stiffness-proportional per group, c = beta_h k; a mode's damping ratio is
//     linear in the betas (sum_h beta_h e_mh lambda_m / (2 omega_m)), so one linear solve gives
//     every assigned mode its group's ratio.
// Repeated until every group's mode is within the tolerance.

#include "simtree/core/tree.h"
#include "simtree/robots/robot_model.h"

namespace simtree::robots::detail {

struct CoupledTuningReport {
  int iterations = 0;
  bool converged = false;
  double worst_frequency_error = 0.0;  // relative, of the last measurement
  double worst_damping_error = 0.0;
  int groups_off = 0;      // branch planes more than 5% off in frequency, of the last measurement
  double omega_max = 0.0;  // the highest eigenfrequency of the tuned tree (rad/s)
  // The lowest eigenvalue (rad/s)^2 of the last solve: negative when the linearised tree is
  // statically unstable under gravity (the tuning stops there).
  double lowest_eigenvalue = 0.0;
  int unstable_modes = 0;  // eigenvalues below zero in the last solve
};

// `gravity`: m/s^2 along -Z the linearisation counts (0: none).
CoupledTuningReport TuneCoupled(const Tree& tree, int max_iterations, double tolerance,
                                double gravity, RobotModel* model);

}  // namespace simtree::robots::detail
