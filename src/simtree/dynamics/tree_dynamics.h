#pragma once
// Modal dynamics of a whole simulation-ready tree (paper Section III-E), built for interactive
// use and for large trees.
//
// The model. Every branch is a curved cantilever in its own frame (u, v, w) with three modes
// (paper Eq. 5-6): bending along u and along w, whose shape is the first Euler-Bernoulli
// cantilever mode (mode_shapes.h), and twist about the chord axis v through the base, growing
// along the arc length. A modal coordinate is the tip deflection (m) or tip twist (rad), so the
// bending modal mass is the material's `mass_kg` and a static tip force F bends the tip by F / k.
// The twist mode's stiffness is `twist_stiffness_ratio` L^2 k (torsion over bending stiffness of a
// round wooden cantilever, 2 G L^2 / 3 E with G/E ~ 1/16) and its inertia follows from its
// frequency.
//
// The hierarchy. A child's base rides its parent's *deformed* attachment node: it is carried to
// that node's position and turned by the parent's rotation there (slope of the bending mode and
// twist), so the tree moves as one. Loads on a branch (rope, wind, weight) drive its own modes and
// reach every ancestor as a force and a moment at the attachment node (pulling a twig bends the
// trunk a little). A child also feels the acceleration of its base (linear and angular: the
// inertial excitation of base-excited cantilevers), so branches the rope never touches swing, as
// in the paper's Fig. 15. The coupling runs parent to child only (the paper treats branches as
// independent systems driven by their parents), so a child's swing does not load its parent and
// every branch keeps its measured frequency and damping. The swings are paid for: the energy the
// drive puts into a family's swings is drawn from what the parent's damping takes out of its
// motion, so the tree's energy never grows without a load, even for a child tuned to its parent
// (modal_step.h).
//
// The cost. One pass per step over the branches in parent-before-child order (level by level, the
// branches of a level in parallel with TBB) places each branch's frame, deforms its nodes and
// advances its children's oscillators. Node data are structure-of-arrays floats with the
// mode-shape values precomputed, so deforming a node is a few multiply-adds and the step is bound
// by memory bandwidth (docs/benchmarks.md, "Dynamics").
//
// The parts, in detail/: branch_model.h (the constants), branch_mechanics.h (mass distribution and
// participations), modal_step.h (the oscillators), pose.h (where branches and points are),
// node_deform.h (the node pass), loads.h and ropes.h (external loads), scheduler.h (the order).
//
// Typical use (the CLI's `simulate`, the viewer):
//   TreeDynamics sim(tree);
//   const int rope = sim.AttachRope({.branch = 3, .anchor = {2, 0, 0}, .force_n = 100});
//   for (...) { sim.Step(1.0 / 60); draw(sim.node_positions()); }
//   sim.ReleaseRope(rope);

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "simtree/core/tree.h"
#include "simtree/dynamics/oscillator.h"
#include "simtree/dynamics/rope.h"
#include "simtree/dynamics/wind.h"

namespace simtree::dynamics {

struct DynamicsOptions {
  Integrator integrator = Integrator::kExact;  // how each modal oscillator is stepped
  // Children feel the acceleration of their base (their parent's attachment node).
  bool base_excitation = true;
  // Loads on a branch reach its ancestors as a force and a moment at each attachment.
  bool transfer_loads = true;
  // Self-weight acts, and the start state (and Reset()) is its static equilibrium: the tree sags
  // from its rest geometry before anything else happens. Off by default: a scanned tree's rest
  // geometry already is its shape under gravity.
  bool gravity = false;
  // Torsional stiffness of a branch over L^2 times its bending stiffness (> 0, no unit):
  // k_twist = ratio L^2 k (N m per rad).
  double twist_stiffness_ratio = 0.04;
  // Give every branch's modes the authors' demo spread: {0.95 f, 1.05 f, f} with damping
  // {1.2 zeta, 0.8 zeta, zeta} (f, zeta the material's twist mode), the Lissajous-like orbits of a
  // real pull test. The materials TreeDynamics::tree() returns carry the spread.
  bool demo_mode_spread = false;
  WindOptions wind;     // off unless wind.enabled
  int max_threads = 0;  // worker threads for the per-step pass (>= 0); 0 = every core TBB finds

  // Throws InputError ("dynamics options", the field) for a value out of range: an unknown
  // integrator, a ratio that is not positive and finite, negative threads, bad wind options.
  void Validate() const;
};

// The three modal coordinates of a branch and their rates: bend_u, bend_w (tip deflection, m)
// and twist_v (tip twist, rad).
struct ModalState {
  std::array<double, 3> q = {0, 0, 0};
  std::array<double, 3> v = {0, 0, 0};
};

// Where a branch is now: its base and the rotation that takes its rest frame to the deformed one
// at its base (so the deformed frame is rotation * (u, v, w) of the rest frame).
struct BranchPose {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Frame frame;  // deformed (u, v, w) at the base
};

// Throws InputError naming `source` and the field when `tree` cannot be simulated: no branches,
// a branch without a material, a frequency that is zero, negative or not finite, a negative or
// NaN damping ratio, a mass or stiffness that is not positive.
void ValidateForSimulation(const Tree& tree, const std::string& source);

class TreeDynamics {
 public:
  // Copies the tree (geometry and materials). Throws InputError for options out of range
  // (options.Validate()) and as ValidateForSimulation(tree, "tree") does.
  explicit TreeDynamics(const Tree& tree, const DynamicsOptions& options = {});
  ~TreeDynamics();
  TreeDynamics(TreeDynamics&&) noexcept;
  TreeDynamics& operator=(TreeDynamics&&) noexcept;

  // The tree as simulated (its materials include live edits and the demo spread).
  const Tree& tree() const;
  const DynamicsOptions& options() const;

  // ---- Time
  // Advances by dt > 0 seconds. Any dt is stable with the exact integrator; changing dt between
  // calls recomputes the step coefficients (one pass over the branches), so keep it fixed.
  void Step(double dt);
  // Advances by `duration` in equal steps no longer than `max_dt`.
  void Advance(double duration, double max_dt);
  double time() const;
  int64_t steps() const;
  // Back to the start: at rest (or at the gravity equilibrium), no ropes, time 0. Materials and
  // wind settings are kept.
  void Reset();
  // Jumps to the static equilibrium under the loads acting now (ropes, gravity, the wind of this
  // instant), with every velocity zero.
  void SettleStatic();

  // ---- Ropes (any number at once)
  // Returns the rope's id. Throws InputError for an unknown branch, an arc length past the tip,
  // or a negative or non-finite force or displacement.
  int AttachRope(const Rope& rope);
  // Moves the anchor or changes the force of a rope (a drag that follows the mouse).
  void UpdateRope(int id, const Rope& rope);
  void ReleaseRope(int id);
  void ReleaseAllRopes();
  bool HasRope(int id) const;
  const Rope& rope(int id) const;
  // The tension the rope pulls with now (N): its force, or the one its displacement needs.
  double RopeTension(int id) const;
  // The rope's point on its branch, where it is now.
  Eigen::Vector3d RopePoint(int id) const;

  // ---- Wind
  void SetWind(const WindOptions& wind);
  void SetWindEnabled(bool enabled);
  void SetWindSpeed(double mean_speed_mps);
  const WindOptions& wind() const;
  // The wind velocity at a point now (the interpolated field the branches feel).
  Eigen::Vector3d WindVelocity(const Eigen::Vector3d& point) const;

  // ---- Materials, live
  const Material& material(int branch) const;
  // Throws InputError (and changes nothing) for a material that cannot be simulated.
  void SetMaterial(int branch, const Material& material);

  // ---- State
  const ModalState& modal_state(int branch) const;
  // Sets a branch's modal state and updates the deformed geometry.
  void SetModalState(int branch, const ModalState& state);
  // Modal energy, kinetic plus elastic, of one branch or of all (J).
  double BranchEnergy(int branch) const;
  double Energy() const;

  // ---- Deformed geometry (current after every Step, Reset, SettleStatic, SetModalState)
  // Every node of every branch, branch by branch in id order, base to tip; world frame, metres.
  std::span<const Eigen::Vector3f> node_positions() const;
  int node_offset(int branch) const;  // index of the branch's first node in node_positions()
  int node_count() const;
  int branch_count() const;
  BranchPose pose(int branch) const;
  // A point of a branch at an arc length from its base (double precision, the same model as the
  // nodes). The rest position of the same point is tree().branches[b].PointAt(s).
  Eigen::Vector3d PointPosition(int branch, double arc_length) const;
  // Rotation from rest to now of the branch's cross-section at a node (its bending slope and
  // twist there, composed with every ancestor's).
  Eigen::Matrix3d NodeRotation(int branch, int node) const;
  // Every node's rotation, in node_positions() order (a pass over the nodes; for skinning).
  void NodeRotations(std::span<Eigen::Quaternionf> out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace simtree::dynamics
