#pragma once
// Small synthetic inputs for the reconstruction tests: cylinder surfaces sampled like a scan,
// hand-made skeletons.

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "simtree/core/units.h"
#include "simtree/reconstruction/detail/local_geometry.h"
#include "simtree/reconstruction/detail/skeleton.h"

namespace simtree::test {

// Points on the surface of a cylinder from `base` along `axis` (length `length`), `spacing` apart
// around and along, with Gaussian noise of `noise` along the normal. Points at angles inside
// [gap_from, gap_to] (radians) are left out (an occlusion).
inline std::vector<Eigen::Vector3d> CylinderPoints(const Eigen::Vector3d& base,
                                                   const Eigen::Vector3d& axis, double length,
                                                   double radius, double spacing,
                                                   double noise = 0.0, uint64_t seed = 1,
                                                   double gap_from = 0.0, double gap_to = 0.0) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const Eigen::Vector3d a = axis.normalized();
  Eigen::Vector3d e1, e2;
  reconstruction::PlaneBasis(a, &e1, &e2);
  const int along = std::max(2, static_cast<int>(length / spacing));
  const int around = std::max(6, static_cast<int>(kTwoPi * radius / spacing));
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= along; ++i) {
    for (int j = 0; j < around; ++j) {
      const double theta = kTwoPi * (j + 0.5 * (i & 1)) / around;
      if (theta >= gap_from && theta <= gap_to) continue;
      const Eigen::Vector3d normal = std::cos(theta) * e1 + std::sin(theta) * e2;
      points.push_back(base + a * (length * i / along) + (radius + noise * gauss(rng)) * normal);
    }
  }
  return points;
}

// A skeleton along a polyline from `from` to `to` in `count` steps, hung on `parent`.
inline int AddSkeletonChain(reconstruction::Skeleton& skeleton, int parent,
                            const Eigen::Vector3d& to, int count, double support = 10.0) {
  const Eigen::Vector3d from = skeleton.nodes[parent].position;
  int last = parent;
  for (int i = 1; i <= count; ++i) {
    reconstruction::SkeletonNode node;
    node.position = from + (to - from) * (static_cast<double>(i) / count);
    node.parent = last;
    node.support = support;
    last = skeleton.size();
    skeleton.nodes.push_back(node);
  }
  return last;
}

// A Y: a 1 m stem along +Z (10 steps) forking at its top into a long branch (0.8 m, 8 steps)
// and a short one (0.3 m, 3 steps).
inline reconstruction::Skeleton YSkeleton() {
  reconstruction::Skeleton s;
  s.nodes.push_back({Eigen::Vector3d::Zero(), -1, 0.0, 10.0, 0.0});
  const int top = AddSkeletonChain(s, 0, {0, 0, 1}, 10);
  AddSkeletonChain(s, top, {0.4, 0, 1.7}, 8);
  AddSkeletonChain(s, top, {-0.2, 0.1, 1.25}, 3);
  return s;
}

}  // namespace simtree::test
