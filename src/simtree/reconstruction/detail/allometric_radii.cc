#include "simtree/reconstruction/detail/allometric_radii.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "simtree/core/option_checks.h"
#include "simtree/core/statistics.h"
#include "simtree/core/units.h"
#include "simtree/reconstruction/detail/local_geometry.h"
#include "simtree/reconstruction/detail/point_index.h"
#include "simtree/reconstruction/detail/trunk_cylinder.h"

namespace simtree::reconstruction {
namespace {

struct LocalFit {
  bool counts = false;
  double radius = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
};

// A circle across the branch at `node` (axis `tangent`) through `points`; counts when the points
// are many, cover enough of the circle, lie on it and agree with the expected radius.
LocalFit FitAcross(const Eigen::Vector3d& node, const Eigen::Vector3d& tangent,
                   const std::vector<Eigen::Vector3d>& points, double expected, double roughness,
                   const RadiusOptions& options) {
  LocalFit fit;
  if (static_cast<int>(points.size()) < options.fit_min_points) return fit;
  if (!FitCircle(points, node, tangent, &fit.centre, &fit.radius)) return fit;
  Eigen::Vector3d e1, e2;
  PlaneBasis(tangent, &e1, &e2);
  std::vector<double> angles;
  double residual2 = 0.0;
  for (const Eigen::Vector3d& p : points) {
    Eigen::Vector3d d = p - fit.centre;
    d -= d.dot(tangent) * tangent;
    residual2 += (d.norm() - fit.radius) * (d.norm() - fit.radius);
    angles.push_back(std::atan2(d.dot(e2), d.dot(e1)));
  }
  std::sort(angles.begin(), angles.end());
  double widest_gap = kTwoPi - (angles.back() - angles.front());
  for (size_t k = 1; k < angles.size(); ++k) {
    widest_gap = std::max(widest_gap, angles[k] - angles[k - 1]);
  }
  const double arc = kTwoPi - widest_gap;
  const double residual = std::sqrt(residual2 / points.size());
  const Eigen::Vector3d offset = (fit.centre - node) - (fit.centre - node).dot(tangent) * tangent;
  fit.counts = arc >= options.fit_min_arc_rad &&
               residual <= options.fit_max_residual * fit.radius + 0.5 * roughness &&
               fit.radius >= options.fit_min_radius_over_noise * roughness &&
               fit.radius <= options.fit_max_ratio * expected &&
               fit.radius >= expected / options.fit_max_ratio && offset.norm() <= 1.5 * fit.radius;
  return fit;
}

}  // namespace

std::vector<double> AllometricWeights(const Skeleton& skeleton, double tip_length_m) {
  std::vector<double> weight(skeleton.nodes.size(), 0.0);
  const auto children = skeleton.Children();
  for (int i = skeleton.size() - 1; i >= 0; --i) {
    if (children[i].empty()) weight[i] = tip_length_m;
    const int p = skeleton.nodes[i].parent;
    if (p >= 0) {
      weight[p] += weight[i] + (skeleton.nodes[i].position - skeleton.nodes[p].position).norm();
    }
  }
  return weight;
}

void RadiusOptions::Validate() const {
  CheckPositive("pipe_exponent", pipe_exponent);
  CheckNonNegative("tip_length_m", tip_length_m);
  CheckPositive("min_radius_m", min_radius_m);
  CheckAtLeast("fit_min_points", fit_min_points, 3);
  CheckInRange("fit_min_arc_rad", fit_min_arc_rad, 0.0, 2 * M_PI);
  CheckPositive("fit_max_residual", fit_max_residual);
  CheckNonNegative("fit_min_radius_over_noise", fit_min_radius_over_noise);
  CheckAtLeast("fit_max_ratio", fit_max_ratio, 1.0);
  CheckAtLeast("max_correction", max_correction, 1.0);
}

void AssignRadii(Skeleton& skeleton, int anchor_node, double anchor_radius_m,
                 double fallback_root_radius_m, std::span<const Eigen::Vector3d> points,
                 double roughness_m, const RadiusOptions& options, RadiusStats* stats) {
  options.Validate();
  RadiusStats local;
  RadiusStats& s = stats ? *stats : local;
  s = {};
  if (skeleton.empty()) return;
  if (anchor_radius_m <= 0.0 || anchor_node < 0 || anchor_node >= skeleton.size()) {
    anchor_node = 0;
    anchor_radius_m = fallback_root_radius_m;
  }
  s.anchor_node = anchor_node;
  s.anchor_radius_m = anchor_radius_m;
  const std::vector<double> weight = AllometricWeights(skeleton, options.tip_length_m);
  const double n = options.pipe_exponent;
  std::vector<double> allometric(skeleton.nodes.size());
  for (int i = 0; i < skeleton.size(); ++i) {
    allometric[i] = std::max(options.min_radius_m,
                             anchor_radius_m * std::pow(weight[i] / weight[anchor_node], 1.0 / n));
  }

  // Points near each node (the nearest node wins).
  const bool fits = options.local_fits && !points.empty() && skeleton.size() > 1;
  std::vector<std::vector<int>> near_node(skeleton.nodes.size());
  if (fits) {
    std::vector<Eigen::Vector3d> positions(skeleton.nodes.size());
    for (int i = 0; i < skeleton.size(); ++i) positions[i] = skeleton.nodes[i].position;
    const PointIndex index(positions);
    std::vector<int> near;
    std::vector<double> d2;
    for (size_t i = 0; i < points.size(); ++i) {
      index.Nearest(points[i], 1, near, d2);
      if (!near.empty()) near_node[near[0]].push_back(static_cast<int>(i));
    }
  }

  const std::vector<SkeletonChain> chains = SkeletonChains(skeleton);
  s.chains = static_cast<int>(chains.size());
  // Ratio of measured to allometric radius per chain, parents first (SkeletonChains lists a
  // chain before the chains that start at its end).
  std::vector<double> ratio_ending_at(skeleton.nodes.size(), 1.0);
  std::vector<double> ratio(skeleton.nodes.size(), 1.0);
  std::vector<Eigen::Vector3d> moved(skeleton.nodes.size());
  std::vector<char> has_move(skeleton.nodes.size(), 0);
  std::vector<Eigen::Vector3d> around;
  for (const SkeletonChain& chain : chains) {
    const auto& ids = chain.nodes;
    const bool has_anchor = std::find(ids.begin(), ids.end(), anchor_node) != ids.end();
    double chain_ratio = ratio_ending_at[ids.front()];
    std::vector<double> ratios;
    for (size_t k = 1; fits && k + 1 < ids.size(); ++k) {
      const int v = ids[k];
      const Eigen::Vector3d tangent =
          skeleton.nodes[ids[k + 1]].position - skeleton.nodes[ids[k - 1]].position;
      if (tangent.norm() < 1e-9) continue;
      // The node's points and its chain neighbours', within half a step along the axis.
      const Eigen::Vector3d t = tangent.normalized();
      const double half = 0.25 * tangent.norm();
      around.clear();
      for (const int u : {ids[k - 1], v, ids[k + 1]}) {
        for (const int i : near_node[u]) {
          if (std::abs((points[i] - skeleton.nodes[v].position).dot(t)) <= half) {
            around.push_back(points[i]);
          }
        }
      }
      const LocalFit fit =
          FitAcross(skeleton.nodes[v].position, t, around, allometric[v], roughness_m, options);
      if (!fit.counts) continue;
      ++s.nodes_fitted;
      ratios.push_back(fit.radius / allometric[v]);
      if (options.recenter_on_fits) {
        // Onto the axis, keeping the node's place along the branch.
        const Eigen::Vector3d d = fit.centre - skeleton.nodes[v].position;
        moved[v] = skeleton.nodes[v].position + d - d.dot(t) * t;
        has_move[v] = 1;
      }
    }
    if (has_anchor) {
      chain_ratio = 1.0;  // the trunk cylinder is the better measurement
    } else if (ratios.size() >= 2) {
      chain_ratio = std::clamp(UpperMedian(ratios, 0.0), 1.0 / options.max_correction,
                               options.max_correction);
      ++s.chains_fitted;
    }
    for (size_t k = 1; k < ids.size(); ++k) ratio[ids[k]] = chain_ratio;
    ratio_ending_at[ids.back()] = chain_ratio;
    if (ids.front() == 0) ratio[0] = chain_ratio;
  }
  for (int i = 0; i < skeleton.size(); ++i) {
    if (has_move[i]) skeleton.nodes[i].position = moved[i];
  }
  // Radii never grow from a node to its child (taper), so a rescaled chain stays inside its parent.
  for (int i = 0; i < skeleton.size(); ++i) {
    double r = std::max(options.min_radius_m, ratio[i] * allometric[i]);
    const int p = skeleton.nodes[i].parent;
    if (p >= 0) r = std::min(r, skeleton.nodes[p].radius);
    skeleton.nodes[i].radius = r;
  }
}

}  // namespace simtree::reconstruction
