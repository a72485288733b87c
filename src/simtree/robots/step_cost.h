#pragma once
// What one MuJoCo step of an exported tree costs, estimated from its joint tree alone. Most of a
// step of a large tree is MuJoCo's sparse factorisations of the joint-space mass matrix (the
// inertia phase and Euler's implicit damping), whose work for a dof grows with the square of the
// dofs on its path to the world; the rest (kinematics, forces) grows with the dof count.
//
//   seconds per step ~ a * dofs + b * sum over dofs of depth^2
//
// a and b are fitted on this project's 2-core machine with bench_robots (docs/benchmarks.md):
// the estimate is a machine-dependent rate, meant for choosing a resolution, not a promise.

#include "simtree/robots/robot_model.h"

namespace simtree::robots {

struct StepCost {
  int dofs = 0;                   // hinges
  double depth_sq_sum = 0.0;      // sum over hinges of (hinges on its path to the world)^2
  double steps_per_second = 0.0;  // estimated (bench_robots' machine)
};

StepCost EstimateStepCost(const RobotModel& model);

}  // namespace simtree::robots
