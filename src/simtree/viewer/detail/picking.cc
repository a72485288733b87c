#include "simtree/viewer/detail/picking.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"

namespace simtree::viewer {
namespace {

// Closest approach of the ray o + t d (t >= 0) and the segment a + s (b - a), s in [0, 1]:
// returns (t, s) and the distance.
double RaySegment(const Ray& ray, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double* t,
                  double* s) {
  const Eigen::Vector3d e = b - a;
  const Eigen::Vector3d w = ray.origin - a;
  const double ee = e.dot(e), de = ray.direction.dot(e), dw = ray.direction.dot(w), ew = e.dot(w);
  const double denom = ee - de * de;  // |d| = 1
  double seg = 0.0;
  if (ee < 1e-18) {
    seg = 0.0;
  } else if (denom > 1e-12 * ee) {
    seg = std::clamp((ew - de * dw) / denom, 0.0, 1.0);
  } else {
    seg = std::clamp(ew / ee, 0.0, 1.0);  // parallel: any point, take the projection of the origin
  }
  const Eigen::Vector3d p = a + seg * e;
  const double along = std::max(0.0, ray.direction.dot(p - ray.origin));
  *t = along;
  *s = seg;
  return (ray.origin + along * ray.direction - p).norm();
}

}  // namespace

void PickOptions::Validate() const {
  CheckOption(std::isfinite(min_radius_px) && min_radius_px >= 0.0, "pick options", "min_radius_px",
              fmt::format("expected a width >= 0 pixels, got {}", min_radius_px));
}

std::optional<BranchHit> PickBranch(const Tree& tree,
                                    std::span<const Eigen::Vector3f> node_positions,
                                    const CameraView& camera, const Ray& ray,
                                    const PickOptions& options) {
  options.Validate();
  if (static_cast<int>(node_positions.size()) != tree.NodeCount()) {
    throw InputError("pick", "node_positions",
                     fmt::format("expected {} nodes (the tree's), got {}", tree.NodeCount(),
                                 node_positions.size()));
  }
  const Eigen::Vector3d forward = camera.Forward();
  std::optional<BranchHit> best;
  size_t first = 0;
  for (const Branch& branch : tree.branches) {
    const std::vector<double> arcs = branch.ArcLengths();
    for (size_t i = 0; i + 1 < branch.nodes.size(); ++i) {
      const Eigen::Vector3d a = node_positions[first + i].cast<double>();
      const Eigen::Vector3d b = node_positions[first + i + 1].cast<double>();
      double t = 0.0, s = 0.0;
      const double miss = RaySegment(ray, a, b, &t, &s);
      const double depth = std::max(1e-6, t * ray.direction.dot(forward));
      const double radius =
          std::max((1.0 - s) * branch.nodes[i].radius + s * branch.nodes[i + 1].radius,
                   options.min_radius_px * camera.PixelSizeAt(depth));
      if (miss > radius || t <= 0.0) continue;
      // The capsule's near surface, so a thick trunk in front wins over a twig behind it.
      const double entry = t - std::sqrt(std::max(0.0, radius * radius - miss * miss));
      if (best && entry >= best->ray_distance) continue;
      best = BranchHit{branch.id, (1.0 - s) * arcs[i] + s * arcs[i + 1], a + s * (b - a), entry};
    }
    first += branch.nodes.size();
  }
  return best;
}

}  // namespace simtree::viewer
