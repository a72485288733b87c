#pragma once
// The tree's branches as closed triangle tubes for ray casting: a ring of vertices at every node,
// carried along the branch by parallel transport, a flat cap at both ends. The rings' vertices lie
// on the true circles and each branch gets enough sides that the facets stay within `tolerance_m`
// of the generalized cylinder (a quarter of the sensor's 1 mm step by default); SensorScene moves
// each hit from its facet onto the exact surface. Embree traces these triangles 2-3 times faster
// than its round curves on this machine (docs/sensor.md), and a new pose only rewrites the
// vertices.
//
// Segments (a branch's node i to node i + 1) are numbered branch by branch, base to tip; the
// triangles of a branch are contiguous: 2 * sides per segment in order, then the base cap and the
// tip cap (sides triangles each).

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "simtree/core/tree.h"
#include "simtree/synth/detail/tree_pose.h"

namespace simtree::synth {

struct TreeTubeOptions {
  double tolerance_m = 0.00025;  // largest gap between a facet and the true surface
  int min_sides = 6;
  int max_sides = 64;
};

// Sides of a ring of `radius` whose chords stay within `tolerance_m` of the circle.
int TubeSides(double radius, const TreeTubeOptions& options);

class TreeTubes {
 public:
  TreeTubes() = default;
  explicit TreeTubes(const Tree& tree, const TreeTubeOptions& options = {});

  int vertex_count() const { return vertex_count_; }
  int triangle_count() const { return static_cast<int>(triangles_.size()); }
  int segment_count() const { return static_cast<int>(segment_branch_.size()); }
  const std::vector<Eigen::Vector3i>& triangles() const { return triangles_; }

  int sides(int branch) const { return sides_[branch]; }
  int vertex_offset(int branch) const { return vertex_offset_[branch]; }
  int branch_vertex_count(int branch) const;
  int triangle_offset(int branch) const { return triangle_offset_[branch]; }
  int first_segment(int branch) const { return first_segment_[branch]; }

  // The segment a triangle belongs to (caps belong to their end's segment), and whether it is a
  // cap.
  int triangle_segment(int triangle) const { return triangle_segment_[triangle]; }
  bool triangle_is_cap(int triangle) const { return triangle_cap_[triangle] != 0; }
  int segment_branch(int segment) const { return segment_branch_[segment]; }
  int segment_node(int segment) const { return segment_node_[segment]; }

  // Writes the vertices of `branch` in `pose` (x, y, z floats, branch_vertex_count(branch) of
  // them) to `out`.
  void WriteBranchVertices(const Tree& tree, const TreePose& pose, int branch, float* out) const;
  // Every branch, at vertex_offset(branch) * 3 floats into `out`.
  void WriteVertices(const Tree& tree, const TreePose& pose, float* out) const;

 private:
  int vertex_count_ = 0;
  std::vector<int> sides_;
  std::vector<int> vertex_offset_;
  std::vector<int> triangle_offset_;
  std::vector<int> first_segment_;
  std::vector<Eigen::Vector3i> triangles_;
  std::vector<int> triangle_segment_;
  std::vector<uint8_t> triangle_cap_;
  std::vector<int> segment_branch_;
  std::vector<int> segment_node_;
};

}  // namespace simtree::synth
