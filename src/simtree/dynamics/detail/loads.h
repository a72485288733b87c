#pragma once
// External loads on the branches: a force and moment at a point of a branch (a rope), the
// branch's own weight and wind drag, and the reactions a branch passes to its parent. Each becomes
// generalised forces on the branch's three modes. Lever arms are rest offsets turned with the
// branch's base (co-rotational): a branch's own deflection does not change how a load acts on it,
// which keeps the model linear in its own modal coordinates.

#include <array>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "simtree/dynamics/detail/branch_model.h"
#include "simtree/dynamics/detail/branch_state.h"
#include "simtree/dynamics/wind.h"

namespace simtree::dynamics {

// The external load of a branch for the current step: generalised forces on its modes (N, N,
// N m), and the force (N) and moment about its base (N m, world) it passes to its parent.
struct Load {
  std::array<double, 3> q = {0, 0, 0};
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
};

// Every branch's load, and which branches carry one (so a step clears only those).
struct LoadTable {
  std::vector<Load> load;
  bool all_loaded = false;  // distributed loads: any branch may carry one
  std::vector<int> loaded;  // otherwise the branches that do

  // Zeroes the loads carried (every load with `everything`).
  void Clear(bool everything = false);
};

// Adds to `out` the generalised forces of a force F and a moment M acting at a point of a branch
// whose deformed base frame is `frame`, given the point's mode-shape values (phi, bending slope
// per metre, psi) and its lever arm r from the branch base (world); and adds F and M + r x F to
// the reaction the branch passes to its parent.
void AddPointLoad(const Eigen::Matrix3d& frame, double phi, double slope, double psi,
                  const Eigen::Vector3d& r, const Eigen::Vector3d& force,
                  const Eigen::Vector3d& moment, Load& out);

// Passes a child's base reaction (force, moment about its base) to its parent, whose deformed
// base frame is `parent_frame`.
void AddChildReaction(const BranchLink& child, const Eigen::Matrix3d& parent_frame,
                      const Eigen::Vector3d& force, const Eigen::Vector3d& moment,
                      Load& parent_load);

// The branch's own distributed loads: its weight (with `gravity`) and the drag of `wind` (when
// enabled, at the lattice it sampled last).
Load OwnDistributedLoad(const BranchMechanics& mechanics, const BranchState& state, bool gravity,
                        const WindField& wind);

// A point force (N, world) at `arc_length` metres along branch `branch`.
struct PointForce {
  int branch = 0;
  double arc_length = 0.0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
};

// Applies a point force to its branch and, with `transfer_loads`, to every ancestor, touching only
// that chain of `loads`; `touched` (may be null) records the branches loaded.
void WalkPointLoad(const DynamicsModel& model, std::span<const BranchState> states,
                   bool transfer_loads, const PointForce& point, std::vector<Load>& loads,
                   std::vector<int>* touched);

}  // namespace simtree::dynamics
