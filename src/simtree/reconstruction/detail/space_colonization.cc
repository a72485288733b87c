#include "simtree/reconstruction/detail/space_colonization.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "simtree/core/option_checks.h"
#include "simtree/reconstruction/detail/point_index.h"

namespace simtree::reconstruction {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

enum class PointState : char { kFree, kReached, kStuck };

struct GrowingNode {
  Eigen::Vector3d position;
  Eigen::Vector3d direction;  // unit
  int parent = -1;
  double geodesic_m = 0.0;
  std::vector<int> children;
  double support = 0.0;
  double thickness_sum = 0.0;
  double thickness = 0.0;  // of the wood here: what it reached, else its parent's
  Eigen::Vector3d reached_sum = Eigen::Vector3d::Zero();  // weighted, of the points it reached
  double beside_weight = 0.0;  // reached beside it on thick wood: not used for recentring
};

class Colonizer {
 public:
  Colonizer(std::span<const AttractionPoint> points, const ColonizationLengths& lengths,
            const ColonizationOptions& options)
      : points_(points),
        lengths_(lengths),
        options_(options),
        bridge_gap_(options.bridge_gaps ? lengths.bridge_gap_m : 0.0),
        index_(Positions(points)),
        state_(points.size(), PointState::kFree),
        best_node_(points.size(), -1),
        best_distance_(points.size(), kInf),
        influence_(points.size()),
        kill_(points.size()) {
    cos_cone_ = options.perception_half_angle_rad >= M_PI
                    ? -2.0
                    : std::cos(options.perception_half_angle_rad);
    use_geodesic_ = options.geodesic_consistency;
    for (size_t i = 0; i < points.size(); ++i) {
      const double t = points[i].thickness_m;
      influence_[i] = std::max(lengths.influence_radius_m, options.influence_per_thickness * t);
      kill_[i] = std::max(lengths.kill_radius_m, options.kill_per_thickness * t);
      max_reach_ = std::max(max_reach_, influence_[i]);
      if (points[i].geodesic_m < 0.0) use_geodesic_ = false;
    }
    max_reach_ = std::max(max_reach_, lengths.kill_radius_m);
    pulls_of_.assign(points.size(), 0);
    max_pulls_ = std::min(
        60000, 8 + static_cast<int>(std::ceil(2.0 * (max_reach_ + bridge_gap_) / lengths.step_m)));
  }

  Skeleton Grow(const Eigen::Vector3d& root, const Eigen::Vector3d& root_direction,
                ColonizationStats& stats) {
    const Eigen::Vector3d up =
        root_direction.norm() > 0 ? root_direction.normalized() : Eigen::Vector3d::UnitZ();
    AddNode(root, up, -1, 0.0);
    for (;;) {
      while (GrowOnce()) {
        ++stats.iterations;
        if (static_cast<int>(nodes_.size()) >= options_.max_nodes) break;
      }
      if (static_cast<int>(nodes_.size()) >= options_.max_nodes || !Bridge(stats)) break;
    }
    for (size_t i = 0; i < points_.size(); ++i) {
      const double w = points_[i].weight;
      if (state_[i] == PointState::kReached) stats.reached_weight += w;
      if (state_[i] == PointState::kStuck) stats.stuck_weight += w;
      if (state_[i] == PointState::kFree) stats.unreached_weight += w;
    }
    Skeleton skeleton;
    skeleton.nodes.reserve(nodes_.size());
    for (const GrowingNode& n : nodes_) {
      SkeletonNode node;
      node.position = n.position;
      node.parent = n.parent;
      node.support = n.support;
      node.thickness = n.thickness;
      // Steps land near, not on, the points; a node that reached points moves onto their centre.
      const double centred = n.support - n.beside_weight;
      if (options_.recenter && centred > 0) node.position = n.reached_sum / centred;
      skeleton.nodes.push_back(node);
    }
    return skeleton;
  }

 private:
  static std::vector<Eigen::Vector3d> Positions(std::span<const AttractionPoint> points) {
    std::vector<Eigen::Vector3d> p(points.size());
    for (size_t i = 0; i < points.size(); ++i) p[i] = points[i].position;
    return p;
  }

  // The distance along the scan from the node to the point is about the straight distance.
  bool GeodesicConsistent(const GrowingNode& node, int point, double distance) const {
    if (!use_geodesic_) return true;
    const double ahead = points_[point].geodesic_m - node.geodesic_m;
    const double slack = lengths_.geodesic_slack_m;
    return ahead >= -slack && ahead <= options_.geodesic_ratio * distance + slack;
  }

  bool Perceives(const GrowingNode& node, int point, double distance) const {
    const Eigen::Vector3d to = points_[point].position - node.position;
    if (distance > 1e-9 && to.dot(node.direction) < cos_cone_ * distance) return false;
    return GeodesicConsistent(node, point, distance);
  }

  // Adds a node, retires the points it reaches and becomes the choice of the points it is now
  // the nearest perceiving node of.
  void AddNode(const Eigen::Vector3d& position, const Eigen::Vector3d& direction, int parent,
               double geodesic) {
    const int id = static_cast<int>(nodes_.size());
    nodes_.push_back({position, direction, parent, geodesic, {}, 0.0, 0.0, 0.0, {0, 0, 0}, 0.0});
    if (parent >= 0) nodes_[parent].children.push_back(id);
    GrowingNode& node = nodes_.back();
    // Reach first: the points within their kill radius retire and tell how thick the wood is.
    index_.WithinRadius(position, max_reach_, near_, d2_);
    for (size_t k = 0; k < near_.size(); ++k) {
      const int i = near_[k];
      const double d = std::sqrt(d2_[k]);
      // Right on top of a point, a node reaches it whatever its geodesic says.
      if (state_[i] != PointState::kFree || d > kill_[i] ||
          (d > 0.5 * kill_[i] && !GeodesicConsistent(node, i, d))) {
        continue;
      }
      state_[i] = PointState::kReached;
      node.support += points_[i].weight;
      node.thickness_sum += points_[i].weight * points_[i].thickness_m;
      node.reached_sum += points_[i].weight * points_[i].position;
    }
    node.thickness = node.support > 0 ? node.thickness_sum / node.support
                                      : (parent >= 0 ? nodes_[parent].thickness : 0.0);
    // Inside thick wood every point beside the node (not ahead of it) nearer the axis than the
    // wood's radius is wood this node stands on: arcs of a ring that occlusion or noise broke.
    // (The thinnest of the node and its two ancestors: the pieces where a fork is still one ring
    // are wider than either branch.)
    double thinnest = node.thickness;
    for (int a = parent, up = 0; a >= 0 && up < 2; a = nodes_[a].parent, ++up) {
      thinnest = std::min(thinnest, nodes_[a].thickness);
    }
    const double node_kill = options_.kill_per_node_thickness * thinnest;
    for (size_t k = 0; node_kill > 0.0 && k < near_.size(); ++k) {
      const int i = near_[k];
      const double d = std::sqrt(d2_[k]);
      if (state_[i] != PointState::kFree || d > node_kill ||
          std::abs((points_[i].position - position).dot(direction)) > 0.5 * lengths_.step_m ||
          !GeodesicConsistent(node, i, d)) {
        continue;
      }
      state_[i] = PointState::kReached;  // counted as support, not as where the axis is
      node.support += points_[i].weight;
      node.beside_weight += points_[i].weight;
    }
    // A thick node perceives further: a branch leaves a trunk at the trunk's surface, about a
    // trunk radius from its axis.
    const double node_reach = options_.influence_per_thickness * node.thickness;
    if (node_reach > max_reach_) index_.WithinRadius(position, node_reach, near_, d2_);
    for (size_t k = 0; k < near_.size(); ++k) {
      const int i = near_[k];
      if (state_[i] != PointState::kFree) continue;
      const double d = std::sqrt(d2_[k]);
      if (d <= std::max(influence_[i], node_reach) && d < best_distance_[i] &&
          Perceives(node, i, d)) {
        if (best_node_[i] < 0) active_.push_back(i);
        best_node_[i] = id;
        best_distance_[i] = d;
      }
    }
  }

  struct Pull {
    int node;
    int point;
  };

  // One synchronous growth step of every node that some free point chose. False when none grew.
  bool GrowOnce() {
    pulls_.clear();
    // A point that has pulled more steps than it takes to cross its reach cannot be reached.
    for (const int i : active_) {
      if (state_[i] == PointState::kFree && ++pulls_of_[i] > max_pulls_) {
        state_[i] = PointState::kStuck;
      }
    }
    std::erase_if(active_, [&](int i) { return state_[i] != PointState::kFree; });
    std::sort(active_.begin(), active_.end());  // the order of growth must not depend on history
    for (const int i : active_) pulls_.push_back({best_node_[i], i});
    if (pulls_.empty()) return false;
    std::stable_sort(pulls_.begin(), pulls_.end(),
                     [](const Pull& a, const Pull& b) { return a.node < b.node; });
    struct NewNode {
      Eigen::Vector3d position, direction;
      int parent;
      double geodesic;
    };
    std::vector<NewNode> grown;
    for (size_t begin = 0; begin < pulls_.size();) {
      const int v = pulls_[begin].node;
      size_t end = begin;
      while (end < pulls_.size() && pulls_[end].node == v) ++end;
      const GrowingNode& node = nodes_[v];
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      double weight = 0.0;
      for (size_t k = begin; k < end; ++k) {
        const AttractionPoint& p = points_[pulls_[k].point];
        sum += p.weight * (p.position - node.position).normalized();
        weight += p.weight;
      }
      Eigen::Vector3d direction = sum;
      bool grows = direction.norm() > 0.1 * weight;
      if (grows) {
        direction.normalize();
        if (node.children.empty() && options_.direction_smoothing > 0.0) {
          direction = ((1.0 - options_.direction_smoothing) * direction +
                       options_.direction_smoothing * node.direction)
                          .normalized();
        }
        const Eigen::Vector3d position = node.position + lengths_.step_m * direction;
        // A step onto an existing child: that child is nearer the points, it takes them over
        // (an ancestor on thicker wood perceives further than its children do).
        int onto = -1;
        for (const int c : node.children) {
          if ((nodes_[c].position - position).norm() < 0.3 * lengths_.step_m) onto = c;
        }
        if (onto >= 0) {
          for (size_t k = begin; k < end; ++k) {
            const int i = pulls_[k].point;
            best_node_[i] = onto;
            best_distance_[i] = (points_[i].position - nodes_[onto].position).norm();
          }
          begin = end;
          continue;
        }
        if (node.children.size() >= 12) grows = false;
        if (grows) {
          double geodesic = node.geodesic_m;
          if (use_geodesic_) {
            double sum_g = 0.0;
            for (size_t k = begin; k < end; ++k) {
              const AttractionPoint& p = points_[pulls_[k].point];
              sum_g += p.weight * (p.geodesic_m - (p.position - position).norm());
            }
            geodesic = std::max(node.geodesic_m, sum_g / weight);
          }
          grown.push_back({position, direction, v, geodesic});
        }
      }
      if (!grows) {
        for (size_t k = begin; k < end; ++k) state_[pulls_[k].point] = PointState::kStuck;
      }
      begin = end;
    }
    for (const NewNode& n : grown) AddNode(n.position, n.direction, n.parent, n.geodesic);
    return true;
  }

  // Points never perceived, grouped by proximity; each group within the bridge gap of a node gets
  // its nearest point assigned to that node. True when something was bridged.
  bool Bridge(ColonizationStats& stats) {
    if (bridge_gap_ <= 0.0) return false;
    std::vector<int> free;
    for (size_t i = 0; i < points_.size(); ++i) {
      if (state_[i] == PointState::kFree) free.push_back(static_cast<int>(i));
    }
    if (free.empty()) return false;
    std::vector<Eigen::Vector3d> node_positions(nodes_.size());
    for (size_t v = 0; v < nodes_.size(); ++v) node_positions[v] = nodes_[v].position;
    const PointIndex node_index(node_positions);
    // Group free points: union of pairs closer than their influence radius.
    std::vector<int> group(points_.size(), -1);
    std::vector<int> root(free.size());
    std::iota(root.begin(), root.end(), 0);
    std::vector<int> slot(points_.size(), -1);
    for (size_t k = 0; k < free.size(); ++k) slot[free[k]] = static_cast<int>(k);
    auto find = [&](int k) {
      while (root[k] != k) k = root[k] = root[root[k]];
      return k;
    };
    for (size_t k = 0; k < free.size(); ++k) {
      const int i = free[k];
      index_.WithinRadius(points_[i].position, influence_[i], near_, d2_);
      for (const int j : near_) {
        if (slot[j] < 0) continue;
        const int a = find(static_cast<int>(k)), b = find(slot[j]);
        if (a != b) root[std::max(a, b)] = std::min(a, b);
      }
    }
    // Per group: the free point nearest to the skeleton, from a node not further along the tree
    // than the point (a bridge never grows back down a branch).
    std::vector<int> best_point(free.size(), -1), best_node(free.size(), -1);
    std::vector<double> best_gap(free.size(), kInf);
    for (size_t k = 0; k < free.size(); ++k) {
      const AttractionPoint& p = points_[free[k]];
      node_index.Nearest(p.position, 16, near_, d2_);
      if (near_.empty()) continue;
      int chosen = use_geodesic_ ? -1 : 0;
      for (size_t c = 0; chosen < 0 && c < near_.size(); ++c) {
        if (nodes_[near_[c]].geodesic_m <= p.geodesic_m + lengths_.geodesic_slack_m) {
          chosen = static_cast<int>(c);
        }
      }
      if (chosen < 0) continue;  // only nodes further along the tree are near: not from there
      const int g = find(static_cast<int>(k));
      const double gap = std::sqrt(d2_[chosen]);
      if (gap < best_gap[g]) {
        best_gap[g] = gap;
        best_point[g] = free[k];
        best_node[g] = near_[chosen];
      }
    }
    bool bridged = false;
    for (size_t g = 0; g < free.size(); ++g) {
      if (best_point[g] < 0 || best_gap[g] > bridge_gap_) continue;
      const int i = best_point[g];
      if (best_node_[i] < 0) active_.push_back(i);
      best_node_[i] = best_node[g];
      best_distance_[i] = best_gap[g];
      // The bridge's new nodes must keep perceiving the point across the whole gap.
      influence_[i] = std::max(influence_[i], best_gap[g] + lengths_.step_m);
      max_reach_ = std::max(max_reach_, influence_[i]);
      ++stats.bridges;
      bridged = true;
    }
    return bridged;
  }

  std::span<const AttractionPoint> points_;
  const ColonizationLengths& lengths_;
  const ColonizationOptions& options_;
  const double bridge_gap_;  // 0 when bridging is off
  PointIndex index_;
  std::vector<PointState> state_;
  std::vector<int> best_node_;
  std::vector<double> best_distance_;
  std::vector<double> influence_, kill_;
  double max_reach_ = 0.0;
  double cos_cone_ = -2.0;
  bool use_geodesic_ = true;
  std::vector<GrowingNode> nodes_;
  std::vector<Pull> pulls_;
  std::vector<int> active_;  // free points some node perceives
  std::vector<uint16_t> pulls_of_;
  int max_pulls_ = 0;
  std::vector<int> near_;
  std::vector<double> d2_;
};

}  // namespace

void ColonizationLengths::Validate() const {
  CheckPositive("step_m", step_m);
  CheckPositive("influence_radius_m", influence_radius_m);
  CheckPositive("kill_radius_m", kill_radius_m);
  CheckNonNegative("geodesic_slack_m", geodesic_slack_m);
  CheckNonNegative("bridge_gap_m", bridge_gap_m);
}

void ColonizationOptions::Validate() const {
  CheckNonNegative("influence_per_thickness", influence_per_thickness);
  CheckNonNegative("kill_per_thickness", kill_per_thickness);
  CheckNonNegative("kill_per_node_thickness", kill_per_node_thickness);
  CheckPositive("perception_half_angle_rad", perception_half_angle_rad);
  CheckShare("direction_smoothing", direction_smoothing);
  CheckPositive("geodesic_ratio", geodesic_ratio);
  CheckAtLeast("max_nodes", max_nodes, 1);
}

Skeleton GrowByColonization(std::span<const AttractionPoint> points, const Eigen::Vector3d& root,
                            const Eigen::Vector3d& root_direction,
                            const ColonizationLengths& lengths, const ColonizationOptions& options,
                            ColonizationStats* stats) {
  lengths.Validate();
  options.Validate();
  ColonizationStats local;
  ColonizationStats& s = stats ? *stats : local;
  s = {};
  if (points.empty()) {
    Skeleton skeleton;
    skeleton.nodes.push_back({root, -1, 0.0, 0.0, 0.0});
    return skeleton;
  }
  Colonizer colonizer(points, lengths, options);
  return colonizer.Grow(root, root_direction, s);
}

}  // namespace simtree::reconstruction
