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
  double leaves_per_metre = 30.0;  // along each terminal branch
  double leaf_length_m = 0.12;     // petiole base to blade tip
  double start_fraction = 0.25;    // leaves from this fraction of the branch length to the tip
  double tilt_rad = 0.8;           // leaf axis from the branch axis towards the radial direction
  double size_jitter = 0.2;        // relative spread of leaf sizes
  double angle_jitter_rad = 0.35;  // spread of the spiral angle and of the roll
  int max_leaves = 20000;          // a cap, spread evenly over the tree
  uint64_t seed = 1;
};

// One leaf in the rest pose: its base point and orientation relative to the node it rides.
struct LeafInstance {
  int node = 0;    // global node index (branch by branch, base to tip, as TreeDynamics numbers)
  int branch = 0;  // the terminal branch it grows on
  Eigen::Vector3f offset = Eigen::Vector3f::Zero();  // base point minus the node's rest position
  Eigen::Quaternionf orientation = Eigen::Quaternionf::Identity();  // leaf frame to world, rest
  float scale = 1.0f;  // multiplies the leaf model (already normalised to leaf_length_m)
};

// Throws InputError for options out of range (NaN, negative density or size, start past 1).
// `model_length` is the leaf model's own length (LeafModel::Length()), so `scale` makes each leaf
// about `leaf_length_m` long.
std::vector<LeafInstance> PlaceLeaves(const Tree& tree, float model_length,
                                      const FoliageOptions& options = {});

// Index of every branch's first node when all nodes are numbered branch by branch (the order of
// TreeDynamics::node_positions()); one more entry at the end holds the total.
std::vector<int> NodeOffsets(const Tree& tree);

}  // namespace simtree::viewer
