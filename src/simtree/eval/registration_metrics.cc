#include "simtree/eval/registration_metrics.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "simtree/core/error.h"

namespace simtree::eval {

std::vector<Eigen::Vector3d> TreeSamplePoints(const Tree& tree, double spacing_m) {
  if (!(spacing_m > 0)) throw InputError("<memory>", "spacing", "expected a positive spacing");
  std::vector<Eigen::Vector3d> points;
  for (const Branch& branch : tree.branches) {
    for (size_t n = 0; n + 1 < branch.nodes.size(); ++n) {
      const Eigen::Vector3d& a = branch.nodes[n].position;
      const Eigen::Vector3d& b = branch.nodes[n + 1].position;
      const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing_m)));
      for (int s = 0; s < steps; ++s) points.push_back(a + (b - a) * (double(s) / steps));
    }
    if (!branch.nodes.empty()) points.push_back(branch.nodes.back().position);
  }
  return points;
}

PoseError ErrorAtTree(const Eigen::Isometry3d& world_error,
                      const std::vector<Eigen::Vector3d>& tree_points) {
  if (tree_points.empty()) {
    throw InputError("<memory>", "tree points", "expected true tree points to measure at");
  }
  PoseError error;
  const Eigen::AngleAxisd angle(world_error.linear());
  error.rotation_deg = std::abs(angle.angle()) * 180.0 / std::numbers::pi;
  double squared = 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : tree_points) {
    const double d = (world_error * p - p).norm();
    squared += d * d;
    error.tree_max_m = std::max(error.tree_max_m, d);
    centroid += p;
  }
  centroid /= static_cast<double>(tree_points.size());
  error.tree_rms_m = std::sqrt(squared / static_cast<double>(tree_points.size()));
  error.centroid_m = (world_error * centroid - centroid).norm();
  return error;
}

PoseError PairPoseError(const Eigen::Isometry3d& estimated_target_from_source,
                        const Eigen::Isometry3d& world_from_source,
                        const Eigen::Isometry3d& world_from_target,
                        const std::vector<Eigen::Vector3d>& tree_points) {
  // World -> source camera (true) -> target camera (estimated) -> world (true).
  const Eigen::Isometry3d world_error =
      world_from_target * estimated_target_from_source * world_from_source.inverse();
  return ErrorAtTree(world_error, tree_points);
}

PoseError ViewPoseError(const Eigen::Isometry3d& frame_from_view,
                        const Eigen::Isometry3d& frame_from_anchor,
                        const Eigen::Isometry3d& world_from_view,
                        const Eigen::Isometry3d& world_from_anchor,
                        const std::vector<Eigen::Vector3d>& tree_points) {
  return PairPoseError(frame_from_anchor.inverse() * frame_from_view, world_from_view,
                       world_from_anchor, tree_points);
}

double ViewAngleDeg(const Eigen::Isometry3d& world_from_a, const Eigen::Isometry3d& world_from_b) {
  // Optical axes on the horizontal plane (world Z is up): the turn around the tree.
  Eigen::Vector3d a = world_from_a.linear().col(2);
  Eigen::Vector3d b = world_from_b.linear().col(2);
  a.z() = 0;
  b.z() = 0;
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / std::numbers::pi;
}

}  // namespace simtree::eval
