#pragma once
// The constants of the modal model, built once from the tree (and again for a branch whose
// material changes): where every node sits in its branch's rest frame with its mode-shape values
// (NodeTables), how each branch hangs on its parent and what a step needs of it (BranchLink), its
// rest geometry and mechanics (BranchModel), and the order a step visits the branches in
// (TreeOrder).
//
// "Frame coordinates" are components along a branch's own rest frame (u, v, w); "parent
// coordinates" along its parent's.

#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "simtree/core/tree.h"
#include "simtree/dynamics/oscillator.h"

namespace simtree::dynamics {

// The three modes, in ModalState and in a material's modes.
inline constexpr int kModeU = 0;  // bend_u
inline constexpr int kModeW = 1;  // bend_w
inline constexpr int kModeT = 2;  // twist_v

// Per node, structure of arrays in node_positions() order: the rest offset from the branch's base
// in its rest frame (h along the chord axis v, a_u and a_w across it) and the mode-shape values
// phi (bending) and psi (twist) at the node's arc length.
struct NodeTables {
  std::vector<float> h, a_u, a_w, phi, psi;
  std::vector<float> arc_fraction;  // s / L, for rotations (not read by the step)
};

// A branch's mass distribution and modal constants, from its material and its nodes' radii.
// Cross-section volumes are scaled to lumped node masses w_j so that sum w phi^2 is the modal mass.
struct BranchMechanics {
  // Weight: total mass (kg) and first moment sum w r (kg m, frame coordinates).
  double mass_total = 0;
  Eigen::Vector3d mass_moment = Eigen::Vector3d::Zero();
  // What a base acceleration a and angular acceleration alpha (frame coordinates) do to the
  // modes: Q_u = -(lin_bend a_u + rot_u . alpha), Q_w likewise with rot_w, Q_t = -twist_rotation
  // alpha_v. lin_bend = sum w phi (kg), rot_u = sum w phi (r x u) (kg m), twist_rotation =
  // participation x twist inertia (kg m^2).
  double lin_bend = 0, twist_rotation = 0;
  Eigen::Vector3d rot_u = Eigen::Vector3d::Zero(), rot_w = Eigen::Vector3d::Zero();
  // What a uniform force field per unit mass g (weight) does to the twist: (R lin_twist) . g, with
  // lin_twist = sum w psi (v x r) (kg m).
  Eigen::Vector3d lin_twist = Eigen::Vector3d::Zero();
  // Wind: projected area (diameter x length, m^2), its mode-shape weighted sums and centroid
  // (frame coordinates).
  double area = 0, area_phi = 0;
  Eigen::Vector3d area_twist = Eigen::Vector3d::Zero();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::array<double, 3> modal_mass = {1, 1, 1};  // kg, kg, kg m^2
  std::array<double, 3> inverse_mass = {1, 1, 1};
  std::array<double, 3> frequency = {1, 1, 1};  // Hz
  std::array<double, 3> damping = {0, 0, 0};
};

// What a step reads of a branch, kept together and small.
struct BranchLink {
  int parent = -1, first_node = 0, nodes = 0;
  // The attachment node on the parent: rest offset from the parent's base (parent coordinates:
  // a_u, h, a_w), the parent's mode shapes there, and this branch's rest frame in parent
  // coordinates.
  double attach_au = 0, attach_h = 0, attach_aw = 0;
  double attach_phi = 0, attach_slope = 0, attach_psi = 0;  // slope per metre
  Eigen::Matrix3d relative_frame = Eigen::Matrix3d::Identity();
  // The base-excitation terms of BranchMechanics, copied here for the step.
  double lin_bend = 0, twist_rotation = 0;
  Eigen::Vector3d rot_u = Eigen::Vector3d::Zero(), rot_w = Eigen::Vector3d::Zero();
  std::array<double, 3> inverse_mass = {1, 1, 1};
  // Half the modal masses and half the modal stiffnesses m w^2: the energy of a state is
  // sum half_mass v^2 + half_stiffness q^2.
  std::array<double, 3> half_mass = {0.5, 0.5, 0.5}, half_stiffness = {0.5, 0.5, 0.5};
  bool has_children = false;           // whether its children's swings draw on it
  std::array<OscillatorStep, 3> step;  // for the step length of the last Step()
  // The share of the swing bank (BranchState) kept over a step: the slowest of the three modes'
  // free energy decay over it, e^(-2 zeta w dt).
  double bank_keep = 1;
};

// The rest of a branch's constants.
struct BranchModel {
  int parent_node = 0, level = 0;
  double length = 0;
  Eigen::Matrix3d frame;  // columns: rest u, v, w (world)
  Eigen::Vector3d rest_base;
  BranchMechanics mechanics;
};

// Parents before children: the branches level by level, and each branch's children.
struct TreeOrder {
  std::vector<int> level_order;  // branch ids by level, then id
  std::vector<int> level_begin;  // level L is level_order[level_begin[L], level_begin[L + 1])
  std::vector<int> child_begin;  // children of b: child_list[child_begin[b], child_begin[b + 1])
  std::vector<int> child_list;
};

// The tree as simulated (its materials include live edits and the demo spread) and its constants.
struct DynamicsModel {
  Tree tree;
  std::vector<BranchLink> links;
  std::vector<BranchModel> models;
  NodeTables nodes;
  TreeOrder order;

  int size() const { return tree.size(); }
};

TreeOrder BuildTreeOrder(const Tree& tree);

// Everything but the mechanics: node tables, attachments, rest frames (parents must come before
// their children in `tree.branches`, as a valid tree has them).
DynamicsModel BuildDynamicsModel(Tree tree);

// Stores `mechanics` in the branch's model and its link.
void SetBranchMechanics(const BranchMechanics& mechanics, BranchModel& model, BranchLink& link);

}  // namespace simtree::dynamics
