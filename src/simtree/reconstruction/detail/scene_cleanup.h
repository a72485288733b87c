#pragma once
// Cleaning a scene cloud (a merged capture that kept the ground and what stands on it) down to the
// tree, once the ground is known: sparse returns that no surface explains (sunlight, flying pixels
// at silhouettes) and the objects that stand on the ground apart from the tree (boxes, posts).
// Segmented tree scans have no ground and are not touched.

#include <span>
#include <vector>

#include <Eigen/Core>

#include "simtree/reconstruction/detail/ground_plane.h"

namespace simtree::reconstruction {

struct SparseReturnOptions {
  double radius_m = 0.01;  // metres, the neighbourhood searched
  int min_neighbours = 6;  // a measured surface has at least this many points that near

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

// Per point: 1 when fewer than `min_neighbours` other points lie within `radius_m`.
std::vector<char> FindSparseReturns(std::span<const Eigen::Vector3d> points,
                                    const SparseReturnOptions& options = {});

struct GroundObjectOptions {
  double neighbour_radius_m = 0.02;  // metres: points closer than this are one object
  double touch_height_m = 0.05;  // metres: an object reaching this close to the ground stands on it

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

// Per point: 1 when it belongs to a connected piece (links up to neighbour_radius_m) that stands
// on the ground and is not the largest such piece (the tree).
std::vector<char> FindObjectsOnGround(std::span<const Eigen::Vector3d> points,
                                      const GroundPlane& ground,
                                      const GroundObjectOptions& options = {});

}  // namespace simtree::reconstruction
