#pragma once
// Generalized cylinders as closed triangle tubes: a ring of vertices at every node of a branch,
// oriented by parallel transport so the tube does not twist, with a cap at each end. A child's
// first node lies on its parent's axis, so its tube starts inside the parent: joints show no gap.

#include <span>

#include "simtree/core/mesh.h"
#include "simtree/core/tree.h"

namespace simtree {

struct TubeMeshOptions {
  int sides = 12;            // vertices per ring (>= 3)
  bool caps = true;          // close both ends
  double min_radius = 1e-4;  // radii below this are drawn at this size (metres)
};

// Appends one closed tube along `centers` with `radii` (same length, >= 2). `reference_u` fixes
// where the first ring starts (projected off the first tangent).
void AppendTube(std::span<const Eigen::Vector3d> centers, std::span<const double> radii,
                const Eigen::Vector3d& reference_u, int branch_id, const TubeMeshOptions& options,
                TriangleMesh& mesh);

// The whole tree at rest: one tube per branch.
TriangleMesh BuildTubeMesh(const Tree& tree, const TubeMeshOptions& options = {});

}  // namespace simtree
