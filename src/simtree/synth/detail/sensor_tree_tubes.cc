#include "simtree/synth/detail/sensor_tree_tubes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <tbb/parallel_for.h>

namespace simtree::synth {

int TubeSides(double radius, const TreeTubeOptions& options) {
  // A chord of a circle of radius r spanning 2 pi / n lies r (1 - cos(pi / n)) inside it.
  const double ratio = std::clamp(1.0 - options.tolerance_m / std::max(radius, 1e-9), -1.0, 1.0);
  const double half_angle = std::acos(ratio);
  const int sides = half_angle > 0.0 ? static_cast<int>(std::ceil(std::numbers::pi / half_angle))
                                     : options.max_sides;
  return std::clamp(sides, options.min_sides, options.max_sides);
}

TreeTubes::TreeTubes(const Tree& tree, const TreeTubeOptions& options) {
  const int branches = tree.size();
  sides_.resize(branches);
  vertex_offset_.resize(branches);
  triangle_offset_.resize(branches);
  first_segment_.resize(branches);
  for (const Branch& b : tree.branches) {
    double thickest = 0.0;
    for (const Node& n : b.nodes) thickest = std::max(thickest, n.radius);
    const int sides = TubeSides(thickest, options);
    const int nodes = static_cast<int>(b.nodes.size());
    sides_[b.id] = sides;
    vertex_offset_[b.id] = vertex_count_;
    triangle_offset_[b.id] = static_cast<int>(triangles_.size());
    first_segment_[b.id] = static_cast<int>(segment_branch_.size());
    const int v0 = vertex_count_;
    auto ring = [&](int node, int k) { return v0 + node * sides + (k % sides); };
    for (int i = 0; i + 1 < nodes; ++i) {
      const int segment = static_cast<int>(segment_branch_.size());
      segment_branch_.push_back(b.id);
      segment_node_.push_back(i);
      for (int k = 0; k < sides; ++k) {
        triangles_.emplace_back(ring(i, k), ring(i, k + 1), ring(i + 1, k + 1));
        triangles_.emplace_back(ring(i, k), ring(i + 1, k + 1), ring(i + 1, k));
        triangle_segment_.insert(triangle_segment_.end(), 2, segment);
        triangle_cap_.insert(triangle_cap_.end(), 2, 0);
      }
    }
    const int base_center = v0 + nodes * sides;
    const int tip_center = base_center + 1;
    const int first = first_segment_[b.id];
    const int last = static_cast<int>(segment_branch_.size()) - 1;
    for (int k = 0; k < sides; ++k) {
      triangles_.emplace_back(base_center, ring(0, k + 1), ring(0, k));
      triangle_segment_.push_back(first);
      triangle_cap_.push_back(1);
    }
    for (int k = 0; k < sides; ++k) {
      triangles_.emplace_back(tip_center, ring(nodes - 1, k), ring(nodes - 1, k + 1));
      triangle_segment_.push_back(last);
      triangle_cap_.push_back(1);
    }
    vertex_count_ += nodes * sides + 2;
  }
}

int TreeTubes::branch_vertex_count(int branch) const {
  const int next = branch + 1 < static_cast<int>(vertex_offset_.size()) ? vertex_offset_[branch + 1]
                                                                        : vertex_count_;
  return next - vertex_offset_[branch];
}

void TreeTubes::WriteBranchVertices(const Tree& tree, const TreePose& pose, int branch,
                                    float* out) const {
  const Branch& b = tree.branches[branch];
  const int nodes = static_cast<int>(b.nodes.size());
  const int sides = sides_[branch];
  auto put = [&out](const Eigen::Vector3d& p) {
    *out++ = static_cast<float>(p.x());
    *out++ = static_cast<float>(p.y());
    *out++ = static_cast<float>(p.z());
  };
  std::vector<double> cosines(sides), sines(sides);
  for (int k = 0; k < sides; ++k) {
    cosines[k] = std::cos(2.0 * std::numbers::pi * k / sides);
    sines[k] = std::sin(2.0 * std::numbers::pi * k / sides);
  }
  // Ring frames by parallel transport from the rest frame's u at the base.
  Eigen::Vector3d e1 = b.frame.u;
  for (int i = 0; i < nodes; ++i) {
    const Eigen::Vector3d& p = pose.node(branch, i);
    const Eigen::Vector3d ahead = pose.node(branch, std::min(i + 1, nodes - 1));
    const Eigen::Vector3d behind = pose.node(branch, std::max(i - 1, 0));
    Eigen::Vector3d tangent = ahead - behind;
    tangent = tangent.norm() > 0 ? Eigen::Vector3d(tangent.normalized()) : Eigen::Vector3d::UnitZ();
    e1 -= e1.dot(tangent) * tangent;
    e1 = e1.norm() > 1e-9 ? Eigen::Vector3d(e1.normalized()) : tangent.unitOrthogonal();
    const Eigen::Vector3d e2 = tangent.cross(e1);
    const double r = b.nodes[i].radius;
    for (int k = 0; k < sides; ++k) put(p + r * (cosines[k] * e1 + sines[k] * e2));
  }
  put(pose.node(branch, 0));
  put(pose.node(branch, nodes - 1));
}

void TreeTubes::WriteVertices(const Tree& tree, const TreePose& pose, float* out) const {
  tbb::parallel_for(0, tree.size(), [&](int b) {
    WriteBranchVertices(tree, pose, b, out + 3 * static_cast<size_t>(vertex_offset_[b]));
  });
}

}  // namespace simtree::synth
