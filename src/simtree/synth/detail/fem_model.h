#pragma once
// The FEM oracle's model of a whole tree: every branch as a chain of 3D Euler-Bernoulli frame
// elements (fem_beam_element.h), 6 degrees of freedom per node, joined rigidly where a branch
// starts (a child's first node *is* its parent's node `parent_node`), held at the trunk's base
// by the ground: clamped, or on a root plate that tilts against a rotational spring.
// It is the synthetic bench's truth of how a tree moves, and it shares nothing with the per-branch
// modal simulator it judges (src/simtree/dynamics/).
//
// Mesh. The tree's nodes become FEM nodes; a segment longer than `max_element_length_m` is split
// into equal elements with interpolated position and radius, so accuracy does not depend on the
// tree file's node spacing. Tree nodes closer than `merge_distance_m` to the previous node of
// their branch share its FEM node (a zero-length segment has no stiffness). Sections are solid
// circles from the node radii, linearly tapered along each element and integrated exactly.
//
// Matrices. Sparse stiffness K and consistent mass M (translational and rotary inertia) over the
// free degrees of freedom, and Rayleigh damping C = alpha M + beta K from the wood. Degrees of
// freedom of node n (n >= 1) are 6 (n - 1) + (u_x, u_y, u_z, theta_x, theta_y, theta_z), world
// axes. The base (node 0) does not move; on a root plate it tilts (theta_x, theta_y: the last two
// degrees of freedom) but neither slides, lifts nor turns about the vertical.
//
// Root plate. A tree's roots and the soil they hold give a little under a sway, so a clamped
// base makes every sway mode stiffer than the tree's, while a turn of the crown about the vertical
// does not tilt the base and is unchanged. The spring is k = ratio E I / H, with E I of the trunk's
// base section and H the height of the highest node above the base: one ratio means the same on a
// tree of any size, and at a fixed ratio every frequency scales as sqrt(E). For a uniform stem
// pulled at its top, the base's tilt gives 3 / (3 + ratio) of the top's deflection.
//
// Small displacements: the model is linear about the rest pose, and poses are the rest nodes
// moved by the displacement (a pull test bends a branch by a few degrees).

#include <array>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "simtree/core/tree.h"
#include "simtree/core/units.h"
#include "simtree/synth/detail/fem_beam_element.h"
#include "simtree/synth/detail/tree_pose.h"
#include "simtree/synth/detail/wood.h"

namespace simtree::synth {

struct FemOptions {
  // Segments longer than this are split into equal elements (metres).
  double max_element_length_m = 0.1;
  // Tree nodes closer than this to the previous node of their branch share its FEM node.
  double merge_distance_m = 1e-6;
  // The root plate's rotational stiffness over the trunk base's E I / H (see above); 0 clamps
  // the base.
  double root_plate_stiffness_ratio = 0.0;
};

// Displacement and small rotation (rotation vector, radians) at a point, world frame.
struct PointMotion {
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();
};

// The linear map from the displacement vector to the motion at one point: motion = rows * x[dofs]
// (rows 0-2 displacement, 3-5 rotation); a dof of -1 is clamped and contributes nothing. Its
// transpose turns a point force and moment into consistent nodal loads.
struct PointMap {
  std::array<int, 12> dofs;
  PointRows rows;
  PointMotion Apply(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  // The 6 x count motion of every column of `shapes` (dof_count x count), e.g. mode shapes.
  Eigen::Matrix<double, 6, Eigen::Dynamic> ApplyToColumns(const Eigen::MatrixXd& shapes) const;
};

class FemModel {
 public:
  // Copies the tree. Throws InputError for an invalid tree (core/validate.h: empty, NaN, zero
  // radius, ...), invalid wood (ValidateWood) or options out of range.
  FemModel(const Tree& tree, const WoodProperties& wood, const FemOptions& options = {});

  const Tree& tree() const { return tree_; }
  const WoodProperties& wood() const { return wood_; }
  const FemOptions& options() const { return options_; }

  int dof_count() const { return 6 * (node_count() - 1) + (has_root_plate() ? 2 : 0); }
  int node_count() const { return static_cast<int>(node_positions_.size()); }
  int element_count() const { return static_cast<int>(elements_.size()); }
  const Eigen::SparseMatrix<double>& stiffness() const { return stiffness_; }
  const Eigen::SparseMatrix<double>& mass() const { return mass_; }
  const Eigen::SparseMatrix<double>& damping() const { return damping_; }
  // The mass of the wood (kg), every element's integral of rho A.
  double total_mass_kg() const { return total_mass_kg_; }
  // The base tilts on a root plate (options().root_plate_stiffness_ratio > 0).
  bool has_root_plate() const { return options_.root_plate_stiffness_ratio > 0; }
  // The root plate's rotational stiffness (N m / rad); 0 when the base is clamped.
  double root_plate_stiffness() const { return root_plate_stiffness_; }

  // ---- Mesh
  const Eigen::Vector3d& node_position(int node) const { return node_positions_[node]; }
  // First degree of freedom of a FEM node whose six all move; -1 for the base (node 0).
  int node_dof(int node) const { return node == 0 ? -1 : 6 * (node - 1); }
  // The six degrees of freedom of a FEM node, -1 where held (the base's, but for its tilt on a
  // root plate).
  std::array<int, 6> node_dofs(int node) const;
  // The FEM node of node `index` of tree branch `branch`.
  int tree_node(int branch, int index) const { return tree_nodes_[branch][index]; }
  const BeamElement& element(int e) const { return elements_[e]; }
  // FEM nodes of element e (a, b).
  std::array<int, 2> element_nodes(int e) const { return element_nodes_[e]; }

  // ---- Loads (vectors over the free degrees of freedom)
  // A force (N) and moment (N m), world frame, at rest arc length `arc_length` of `branch`, as
  // consistent nodal loads. Throws InputError for an unknown branch, an arc length outside the
  // branch (1 mm of slack at the tip, as markers have) or a value that is not finite.
  Eigen::VectorXd PointLoad(int branch, double arc_length, const Eigen::Vector3d& force,
                            const Eigen::Vector3d& moment = Eigen::Vector3d::Zero()) const;
  // The tree's own weight under `gravity` (m/s^2, world), consistent nodal loads.
  Eigen::VectorXd GravityLoad(const Eigen::Vector3d& gravity = {0, 0, -kGravity}) const;

  // ---- Maps back
  // The tree's nodes (TreePose order) moved by displacement vector x.
  TreePose Pose(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  // Displacement and rotation at a rest arc length of a branch (interpolated with the element's
  // shape functions). Throws InputError as PointLoad does.
  PointMotion MotionAt(const Eigen::Ref<const Eigen::VectorXd>& x, int branch,
                       double arc_length) const;
  PointMap PointMapAt(int branch, double arc_length) const;
  // The map of a FEM node's own six degrees of freedom (identity rows; node_dofs(node)).
  PointMap NodeMap(int node) const;

 private:
  void BuildMesh();
  void Assemble();
  // Element of `branch` containing rest arc length s and the fraction along it; element -1 when
  // the branch has no element (every node merged into its base).
  std::pair<int, double> Locate(int branch, double arc_length) const;
  void CheckPoint(int branch, double arc_length, const char* what) const;
  void Scatter(const PointMap& map, const Eigen::Matrix<double, 6, 1>& load,
               Eigen::VectorXd& f) const;

  Tree tree_;
  WoodProperties wood_;
  FemOptions options_;

  std::vector<Eigen::Vector3d> node_positions_;
  std::vector<std::vector<int>> tree_nodes_;  // per branch, per tree node: FEM node
  std::vector<BeamElement> elements_;
  std::vector<std::array<int, 2>> element_nodes_;
  // Per branch: rest arc length at each station (FEM node along the branch, base first) and the
  // element that starts at each station but the last.
  struct Station {
    int node = 0;
    double arc_length = 0.0;
  };
  std::vector<std::vector<Station>> stations_;
  std::vector<int> first_element_;  // per branch; elements of a branch are consecutive

  Eigen::SparseMatrix<double> stiffness_, mass_, damping_;
  double total_mass_kg_ = 0.0;
  double root_plate_stiffness_ = 0.0;
};

}  // namespace simtree::synth
