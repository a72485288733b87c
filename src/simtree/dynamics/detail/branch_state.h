#pragma once
// What changes every step for a branch: its modal coordinates and where its base is now.

#include <array>

#include <Eigen/Core>

#include "simtree/dynamics/tree_dynamics.h"

namespace simtree::dynamics {

struct BranchState {
  ModalState modal;                                // primary + swing: what the geometry shows
  ModalState primary;                              // response to external loads
  ModalState swing;                                // response to the base's acceleration
  std::array<double, 3> acceleration = {0, 0, 0};  // primary, over the last step
  // The deformed frame at the base: columns are the world directions of u, v, w now.
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d base_acceleration = Eigen::Vector3d::Zero();  // world, linear
  Eigen::Vector3d base_angular_acceleration = Eigen::Vector3d::Zero();
  // What this branch's children's swings may draw this step (J): what its damping takes out of
  // its motion over the step, plus its bank.
  double swing_budget = 0;
  // What its damping took out of its motion earlier and its children have not drawn yet (J),
  // fading as fast as its own motion does.
  double swing_bank = 0;
};

}  // namespace simtree::dynamics
