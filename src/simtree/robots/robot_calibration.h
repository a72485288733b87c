#pragma once
// Stiffness and damping for every hinge of a RobotModel, so that each branch's chain rings at
// its material's frequencies with its damping ratios, the sub-tree riding on it counted.
//
// Per branch and per hinge kind (bend_u, bend_w, twist), the linearised chain about its rest pose
// is (K + G) q = w^2 M q over that kind's hinges: M from the bodies each hinge swings (the
// branch's own segments beyond it and every sub-tree attached to them, carried rigidly), G
// gravity's stiffness on them (an upright twig is an inverted pendulum: springs tuned without it
// left tree01 statically unstable), K = s diag(kappa), kappa the stiffness profile along the
// branch ((r_j / r_0)^exponent: 0 is a uniform beam, 4 a beam of one wood). s is set so the
// lowest eigenvalue is (2 pi f)^2; damping is stiffness-proportional, c = beta k, beta giving
// that mode exactly zeta. The parent is held still in this problem. The whole tree's coupled
// tuning (detail/coupled_tuning.h) would then retune every branch plane on the free tree's modes;
// it is off by default (it does not converge on tree01 yet, tests/robots/coupled_tuning_test.cc).
//
// The chains tuned, the whole tree's K + G must still be positive definite (a twist and a side
// branch's bending can fall together): detail/gravity_floor.h stiffens the few hinges of a
// negative direction until it is.
//
// Each hinge's spring reference balances gravity at the rest pose, so the exported tree hangs as
// it was scanned (a scan is already the tree under its weight).

#include "simtree/core/tree.h"
#include "simtree/robots/robot_model.h"

namespace simtree::robots {

struct CalibrationOptions {
  double stiffness_exponent = 0.0;  // hinge stiffness along a branch as (r_j / r_0)^exponent
  double gravity = 9.81;            // m/s^2 the spring references balance (0: none)
  double time_step_s = 0.0;         // simulator step (s); 0 = from the stiffest chain mode
  // Automatic step: omega_max * dt at most this, omega_max the highest chain eigenfrequency.
  double step_safety = 0.5;
  // The whole tree's coupled tuning (detail/coupled_tuning.h): Newton iterations at most (0:
  // none, the default until it converges on tree01), on trees of at most `coupled_max_hinges`
  // hinges (a dense eigenproblem of that size), until every branch plane's mode is within
  // `coupled_tolerance` of its frequency and damping ratio.
  int coupled_iterations = 0;
  int coupled_max_hinges = 1500;
  double coupled_tolerance = 0.01;
  double max_time_step_s = 0.002;
  // The whole tree's stability under gravity (detail/gravity_floor.h) is checked and restored on
  // trees of at most this many hinges (a dense eigenproblem of that size; tree01 has 844).
  int stability_max_hinges = 1500;

  void Validate() const;  // throws OptionError naming the field
};

struct CalibrationReport {
  bool coupled = false;  // the coupled tuning ran
  int coupled_iterations = 0;
  bool coupled_converged = false;
  double worst_frequency_error = 0.0;  // relative, of the coupled linear model (when it ran)
  double worst_damping_error = 0.0;
  int groups_off = 0;  // branch bending planes more than 5% off in frequency (linear model)
  double lowest_eigenvalue = 0.0;  // of the whole tree's linearisation, gravity counted (when run)
  int unstable_modes = 0;          // its eigenvalues below zero
  // The whole tree's stability under gravity (detail/gravity_floor.h), on trees of at most
  // stability_max_hinges hinges: hinges stiffened to keep K + G positive definite, the largest
  // relative raise, and K + G's lowest eigenvalue after (N m / rad).
  bool gravity_checked = false;
  int gravity_stiffened_hinges = 0;
  double gravity_largest_raise = 0.0;
  double gravity_lowest_stiffness = 0.0;
};

// Fills every hinge's stiffness, damping and spring reference, and model->time_step_s and
// model->gravity. `tree` is the one the model was built from.
CalibrationReport CalibrateRobotModel(const Tree& tree, const CalibrationOptions& options,
                                      RobotModel* model);

}  // namespace simtree::robots
