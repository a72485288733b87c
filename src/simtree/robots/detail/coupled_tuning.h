#pragma once
// The whole tree's coupled tuning (robot_calibration.h): the chains are calibrated one by one
// with their parents held still and their sub-trees rigid, but in the free tree a branch swings
// its children and they swing it back, which moves its ringing (tree01: +27% on a first-level
// branch). This linearises the whole tree (joint-space M, K, C about the rest pose), finds for
// every branch and bending plane the mode a pull at its tip rings in (the largest
// (tip displacement along the plane)^2 / eigenvalue), and scales that branch's stiffness and
// damping in that plane until the mode has the branch's frequency and damping ratio.

#include "simtree/core/tree.h"
#include "simtree/robots/robot_model.h"

namespace simtree::robots::detail {

struct CoupledTuningReport {
  int iterations = 0;
  double worst_frequency_error = 0.0;  // relative, after the last iteration
  double worst_damping_error = 0.0;
  int groups_off = 0;      // branch planes more than 5% off in frequency, after the last iteration
  double omega_max = 0.0;  // the highest eigenfrequency of the tuned tree (rad/s)
};

CoupledTuningReport TuneCoupled(const Tree& tree, int max_iterations, double tolerance,
                                RobotModel* model);

}  // namespace simtree::robots::detail
