#pragma once
// Static stability of the whole exported tree under gravity. Each chain's springs are tuned with
// the sub-trees it carries held rigid, so a branch whose twist swings a side branch that can
// also bend (tree01: branch 71's twist with its child 91's bending) can still fall together
// with it: K + G of the whole tree (joint_space_model.h) has a negative direction, an inverted
// pendulum no single chain sees. This stiffens the hinges that direction moves, each in
// proportion to its share of it (the smallest change that lifts it), until K + G is positive
// definite; their spring references and stiffness-proportional damping follow. A tree already
// stable is left as tuned.

#include "simtree/robots/robot_model.h"

namespace simtree::robots::detail {

struct GravityFloorReport {
  bool checked = false;  // the tree was small enough (max_hinges) and had gravity
  int iterations = 0;    // corrections made
  int stiffened_hinges = 0;
  double largest_raise = 0.0;                // the largest relative stiffness increase of a hinge
  double lowest_stiffness_eigenvalue = 0.0;  // of K + G after (N m / rad)
};

// `gravity` along -Z (m/s^2); trees of more than `max_hinges` hinges are not checked (a dense
// eigenproblem of that size per correction).
GravityFloorReport RaiseGravityFloor(double gravity, int max_hinges, RobotModel* model);

}  // namespace simtree::robots::detail
