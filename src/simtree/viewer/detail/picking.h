#pragma once
// Which branch is under the mouse: the ray through a pixel against every segment of the deformed
// tree, each a capsule of the segment's radius (grown to a few pixels so thin twigs can be
// caught). The nearest hit along the ray wins.

#include <optional>
#include <span>

#include <Eigen/Core>

#include "simtree/core/tree.h"
#include "simtree/viewer/detail/camera.h"

namespace simtree::viewer {

struct PickOptions {
  double min_radius_px = 4.0;  // a capsule is at least this wide where it is hit (pixels, >= 0)

  // Throws InputError ("pick options", the field) for a value out of range.
  void Validate() const;
};

struct BranchHit {
  int branch = -1;
  double arc_length = 0.0;  // rest arc length from the branch base (m), where the ray passes
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // on the deformed axis
  double ray_distance = 0.0;                        // from the ray origin (m)
};

// `node_positions`: the deformed nodes, branch by branch, base to tip (TreeDynamics order); the
// rest tree gives the arc lengths. Throws InputError when the node count does not match the tree
// or for options out of range.
std::optional<BranchHit> PickBranch(const Tree& tree,
                                    std::span<const Eigen::Vector3f> node_positions,
                                    const CameraView& camera, const Ray& ray,
                                    const PickOptions& options = {});

}  // namespace simtree::viewer
