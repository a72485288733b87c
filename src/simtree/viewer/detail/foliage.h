#pragma once
// Where the leaves go: along the outer part of every terminal branch (a branch with no children),
// spiralling around it by the golden angle as alternate phyllotaxis does, tilted towards the tip,
// their upper side turned to the sky. Each leaf rides one node of its branch, so when the tree
// moves a leaf follows that node's position and rotation (the renderer skins it on the GPU).

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "simtree/core/tree.h"

namespace simtree::viewer {

struct FoliageOptions {
  double leaves_per_metre = 30.0;  // along each terminal branch (1/m, >= 0)
  double leaf_length_m = 0.12;     // petiole base to blade tip (m, > 0)
  double start_fraction = 0.25;    // leaves from this fraction of the branch length on (in [0, 1))
  double tilt_rad = 0.8;     // leaf axis from the branch axis towards the radial direction (rad)
  double size_jitter = 0.2;  // relative spread of leaf sizes (in [0, 1))
  double angle_jitter_rad = 0.35;  // spread of the spiral angle and of the roll (rad, >= 0)
  int max_leaves = 20000;          // a cap (>= 0), spread evenly over the tree
  uint64_t seed = 1;               // same seed, same leaves

  // Throws InputError ("foliage options", the field) for a value out of range.
  void Validate() const;
};

// One leaf in the rest pose: its base point and orientation relative to the node it rides.
struct LeafInstance {
  int node = 0;    // global node index (branch by branch, base to tip, as TreeDynamics numbers)
  int branch = 0;  // the terminal branch it grows on
  Eigen::Vector3f offset = Eigen::Vector3f::Zero();  // base point minus the node's rest position
  Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();  // leaf frame to world, rest
  float scale = 1.0f;  // multiplies the leaf model (already normalised to leaf_length_m)
};

// Throws InputError for options out of range (options.Validate()) or a model length that is not
// positive. `model_length` is the leaf model's own length (LeafModel::Length()), so `scale` makes
// each leaf about `leaf_length_m` long.
std::vector<LeafInstance> PlaceLeaves(const Tree& tree, float model_length,
                                      const FoliageOptions& options = {});

// Index of every branch's first node when all nodes are numbered branch by branch (the order of
// TreeDynamics::node_positions()); one more entry at the end holds the total.
std::vector<int> NodeOffsets(const Tree& tree);

}  // namespace simtree::viewer
