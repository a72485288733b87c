#include "simtree/synth/detail/marker_placement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <tuple>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "simtree/core/error.h"
#include "simtree/core/units.h"
#include "simtree/synth/detail/segment_grid.h"

namespace simtree::synth {
namespace {

struct Site {
  int branch = 0;
  int node = 0;
  double arc = 0.0;
  double score = 0.0;
  bool visible = true;
};

// Every site of the tree (header), branch by branch, base to tip.
std::vector<Site> FindSites(const Tree& tree, const std::vector<std::vector<int>>& children,
                            const MarkerPlacementOptions& options) {
  std::vector<Site> sites;
  for (const Branch& b : tree.branches) {
    const std::vector<double> arcs = b.ArcLengths();
    const double length = arcs.back();
    for (size_t i = 1; i + 1 < b.nodes.size(); ++i) {
      const double r = b.nodes[i].radius;
      if (r < options.min_radius_m) continue;
      const double clear = std::max(options.fork_clearance_m, 3.0 * r);
      bool ok = arcs[i] >= clear && length - arcs[i] >= clear;
      for (const int c : children[b.id]) {
        ok = ok && std::abs(arcs[tree.branches[c].parent_node] - arcs[i]) >= clear;
      }
      for (const auto& [branch, arc] : options.excluded_sites) {
        ok = ok && !(branch == b.id && std::abs(arc - arcs[i]) < 2.0 * options.fork_clearance_m);
      }
      if (ok) sites.push_back({b.id, static_cast<int>(i), arcs[i]});
    }
  }
  return sites;
}

// Every branch segment of the tree, for the line-of-sight test.
SegmentGrid TreeSegments(const Tree& tree) {
  SegmentGrid grid(0.15);
  for (const Branch& b : tree.branches) {
    for (size_t i = 1; i < b.nodes.size(); ++i) {
      grid.Add({b.nodes[i - 1].position, b.nodes[i].position,
                std::max(b.nodes[i - 1].radius, b.nodes[i].radius), b.id, static_cast<int>(i - 1)});
    }
  }
  return grid;
}

// The tape band's length along the branch (sensor_scene.h's default tape width).
constexpr double kTapeLengthM = 0.04;

// True when most of the band's face towards the camera is clear of every other branch: 9 points
// (3 along the tape, 3 across the branch as the camera sees it), at least 6 of them clear. One
// line of sight to the band's centre let a branch or the trunk hide most of a band.
bool SeenFrom(const Tree& tree, const SegmentGrid& grid, const Site& site,
              const Eigen::Vector3d& camera) {
  const Branch& b = tree.branches[site.branch];
  const Node& node = b.nodes[site.node];
  const Eigen::Vector3d tangent =
      (b.nodes[site.node + 1].position - b.nodes[site.node - 1].position).normalized();
  const Eigen::Vector3d to_camera = (camera - node.position).normalized();
  Eigen::Vector3d across = tangent.cross(to_camera);
  across = across.norm() > 1e-9 ? Eigen::Vector3d(across.normalized()) : Eigen::Vector3d::Zero();
  constexpr int kNeeded = 6;  // of 9
  int clear = 0, blocked = 0;
  for (int k = 0; k < 9 && clear < kNeeded && blocked <= 9 - kNeeded; ++k) {
    const double along = 0.4 * (k / 3 - 1), side = 0.6 * (k % 3 - 1);
    const Eigen::Vector3d centre = node.position + along * kTapeLengthM * tangent;
    const Eigen::Vector3d surface =
        centre + node.radius * (side * across + std::sqrt(1.0 - side * side) * to_camera);
    const bool hidden = grid.AnyNear(camera, surface, grid.max_radius(), [&](const GridSegment& s) {
      if (s.branch == site.branch && std::abs(s.index - site.node) <= 2) return false;
      // Joints at the site's own branch (a child starting next to it) are not occluders.
      if (SegmentDistance(s.a, s.b, node.position, node.position) < 2.0 * node.radius) return false;
      return SegmentDistance(camera, surface, s.a, s.b) < s.radius;
    });
    (hidden ? blocked : clear) += 1;
  }
  return clear >= kNeeded;
}

void ScoreSites(const Tree& tree, std::vector<Site>& sites, const MarkerPlacementOptions& options) {
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> jitter(0.0, 0.2);
  std::optional<SegmentGrid> grid;
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  if (options.camera_position) grid = TreeSegments(tree);
  for (Site& site : sites) {
    const Branch& b = tree.branches[site.branch];
    const Eigen::Vector3d& p = b.nodes[site.node].position;
    const double fraction = site.arc / std::max(1e-9, b.Length());
    site.score = 0.5 * (1.0 - 2.0 * std::abs(fraction - 0.5)) + jitter(rng);
    if (!options.camera_position) continue;
    const Eigen::Vector3d& camera = *options.camera_position;
    site.visible = SeenFrom(tree, *grid, site, camera);
    Eigen::Vector2d out = (p - centre).head<2>(), towards = (camera - centre).head<2>();
    const double facing = out.norm() > 1e-9 && towards.norm() > 1e-9
                              ? out.normalized().dot(towards.normalized())
                              : 0.0;
    const Eigen::Vector3d view = (p - camera).normalized();
    const Eigen::Vector3d tangent =
        (b.nodes[site.node + 1].position - b.nodes[site.node - 1].position).normalized();
    const double across = 1.0 - std::abs(view.dot(tangent));
    site.score += (site.visible ? 2.0 : 0.0) + 0.5 * facing + 0.5 * across;
  }
}

class Placer {
 public:
  Placer(const Tree& tree, const MarkerPlacementOptions& options)
      : tree_(tree), options_(options), children_(tree.Children()) {
    sites_ = FindSites(tree, children_, options);
    ScoreSites(tree, sites_, options);
    sites_of_.resize(tree.size());
    for (int i = 0; i < static_cast<int>(sites_.size()); ++i) {
      sites_of_[sites_[i].branch].push_back(i);
    }
    // Deepest level with a site in each branch's subtree (children have larger ids).
    reach_.assign(tree.size(), -1);
    for (int id = tree.size() - 1; id >= 0; --id) {
      if (!sites_of_[id].empty()) reach_[id] = tree.branches[id].level;
      for (const int c : children_[id]) reach_[id] = std::max(reach_[id], reach_[c]);
    }
  }

  std::vector<int> Choose() {
    ChooseRoot();
    const int deepest = reach_[0];
    const int per_chain = std::max(1, deepest);  // levels 1..deepest
    const int chains = std::max(1, (options_.count - 1) / per_chain);
    for (int k = 0; k < chains && Remaining() > 0; ++k) {
      if (!AddChain()) break;
    }
    FillRest();
    return chosen_;
  }

  int site_count() const { return static_cast<int>(sites_.size()); }
  const Site& site(int i) const { return sites_[i]; }

 private:
  int Remaining() const { return options_.count - static_cast<int>(chosen_.size()); }

  double ArcOfNode(int branch, int node) const {
    const Branch& b = tree_.branches[branch];
    double arc = 0.0;
    for (int i = 1; i <= node; ++i) arc += (b.nodes[i].position - b.nodes[i - 1].position).norm();
    return arc;
  }

  // The best site of `branch` with arc length below `limit` (-1 when none).
  int BestSite(int branch, double limit = std::numeric_limits<double>::infinity()) const {
    int best = -1;
    for (const int i : sites_of_[branch]) {
      if (sites_[i].arc < limit && (best < 0 || sites_[i].score > sites_[best].score)) best = i;
    }
    return best;
  }

  void Take(int site) {
    chosen_.push_back(site);
    used_branches_.insert(sites_[site].branch);
  }

  void ChooseRoot() {
    double lowest = std::numeric_limits<double>::infinity();
    for (const int c : children_[0]) {
      lowest = std::min(lowest, ArcOfNode(0, tree_.branches[c].parent_node));
    }
    int root = BestSite(0, lowest - options_.fork_clearance_m);
    if (root < 0) root = BestSite(0);
    if (root < 0) {
      throw InputError("PlaceMarkers", "branches[0]",
                       fmt::format("no site for the root marker on the trunk (radius >= {} m, "
                                   "away from forks)",
                                   options_.min_radius_m));
    }
    Take(root);
  }

  // Horizontal direction of a site from the trunk base.
  double Azimuth(int site) const {
    const Eigen::Vector3d& p =
        tree_.branches[sites_[site].branch].nodes[sites_[site].node].position;
    return std::atan2(p.y(), p.x());
  }

  // A chain from a level-1 branch down the hierarchy; false when no level-1 branch is left.
  bool AddChain() {
    // The level-1 branch: best site score plus angular distance from the chains so far.
    int start = -1;
    double start_value = -1e9;
    for (const int c : children_[0]) {
      if (used_branches_.contains(c) || reach_[c] < 1 || sites_of_[c].empty()) continue;
      const int s = BestSite(c);
      double spread = kPi;
      for (const int other : chain_heads_) {
        spread = std::min(spread, std::abs(std::remainder(Azimuth(s) - Azimuth(other), kTwoPi)));
      }
      const double value = sites_[s].score + reach_[c] + 1.5 * spread / kPi;
      if (value > start_value) {
        start_value = value;
        start = c;
      }
    }
    const std::optional<int> wanted = options_.first_chain_branch;
    if (chain_heads_.empty() && wanted && *wanted > 0 && *wanted < tree_.size() &&
        tree_.branches[*wanted].level == 1 && !sites_of_[*wanted].empty()) {
      start = *wanted;
    }
    if (start < 0) return false;
    // Follow the hierarchy down: branches, then one site on each before the next one's fork.
    std::vector<int> branches = {start};
    while (static_cast<int>(branches.size()) < Remaining()) {
      const int b = branches.back();
      int next = -1;
      for (const int c : children_[b]) {
        if (used_branches_.contains(c) || reach_[c] < 0) continue;
        const double attach = ArcOfNode(b, tree_.branches[c].parent_node);
        if (BestSite(b, attach - options_.fork_clearance_m) < 0) continue;
        const int s = BestSite(c);
        if (next < 0 || reach_[c] > reach_[next] ||
            (reach_[c] == reach_[next] && s >= 0 &&
             (BestSite(next) < 0 || sites_[s].score > sites_[BestSite(next)].score))) {
          next = c;
        }
      }
      if (next < 0) break;
      branches.push_back(next);
    }
    // Branches without a site of their own (a thin link in the chain) are skipped over.
    bool first = true;
    for (size_t k = 0; k < branches.size() && Remaining() > 0; ++k) {
      const double limit =
          k + 1 < branches.size()
              ? ArcOfNode(branches[k], tree_.branches[branches[k + 1]].parent_node) -
                    options_.fork_clearance_m
              : std::numeric_limits<double>::infinity();
      const int s = BestSite(branches[k], limit);
      if (s < 0) continue;
      Take(s);
      if (first) chain_heads_.push_back(s);
      first = false;
    }
    return true;
  }

  // The rest by score, one per branch, preferring levels with few markers and sites away from
  // the markers already placed.
  void FillRest() {
    while (Remaining() > 0) {
      std::vector<int> per_level(tree_.MaxLevel() + 1, 0);
      for (const int s : chosen_) ++per_level[tree_.branches[sites_[s].branch].level];
      int best = -1;
      double best_value = -1e9;
      for (int i = 0; i < static_cast<int>(sites_.size()); ++i) {
        if (used_branches_.contains(sites_[i].branch)) continue;
        const Eigen::Vector3d& p = tree_.branches[sites_[i].branch].nodes[sites_[i].node].position;
        double nearest = 1e9;
        for (const int s : chosen_) {
          nearest = std::min(
              nearest,
              (p - tree_.branches[sites_[s].branch].nodes[sites_[s].node].position).norm());
        }
        const double value = sites_[i].score + std::min(nearest, 0.5) * 2.0 -
                             0.5 * per_level[tree_.branches[sites_[i].branch].level];
        if (value > best_value) {
          best_value = value;
          best = i;
        }
      }
      if (best < 0) break;
      Take(best);
    }
  }

  const Tree& tree_;
  const MarkerPlacementOptions& options_;
  std::vector<std::vector<int>> children_;
  std::vector<Site> sites_;
  std::vector<std::vector<int>> sites_of_;
  std::vector<int> reach_;
  std::vector<int> chosen_;
  std::vector<int> chain_heads_;
  std::set<int> used_branches_;
};

// The nearest marker on the way from `m` down to the trunk base (-1 when none).
int NearestMarkerBelow(const Tree& tree, const std::vector<Marker>& markers, const Marker& m) {
  int branch = m.branch;
  double limit = m.arc_length;
  bool strict = true;  // on the marker's own branch, only markers strictly below it
  while (branch >= 0) {
    int best = -1;
    for (const Marker& other : markers) {
      if (other.id == m.id || other.branch != branch) continue;
      const bool below = strict ? other.arc_length < limit : other.arc_length <= limit;
      if (below && (best < 0 || other.arc_length > markers[best].arc_length)) best = other.id;
    }
    if (best >= 0) return best;
    const Branch& b = tree.branches[branch];
    if (b.is_trunk()) break;
    limit = tree.branches[b.parent].ArcLengths()[b.parent_node];
    branch = b.parent;
    strict = false;
  }
  return -1;
}

}  // namespace

MarkerPlacementResult PlaceMarkers(Tree& tree, const MarkerPlacementOptions& options) {
  if (options.count < 1 || !(options.min_radius_m > 0) || !(options.fork_clearance_m >= 0)) {
    throw InputError("MarkerPlacementOptions", "",
                     "expected count >= 1, min_radius_m > 0 and fork_clearance_m >= 0");
  }
  if (tree.empty()) throw InputError("PlaceMarkers", "branches", "expected a tree with a trunk");
  Placer placer(tree, options);
  std::vector<int> chosen = placer.Choose();
  // Parents first: by level, then branch, then arc length.
  std::sort(chosen.begin(), chosen.end(), [&](int a, int b) {
    const Site &sa = placer.site(a), &sb = placer.site(b);
    const int la = tree.branches[sa.branch].level, lb = tree.branches[sb.branch].level;
    return std::tie(la, sa.branch, sa.arc) < std::tie(lb, sb.branch, sb.arc);
  });
  MarkerPlacementResult result;
  result.sites = placer.site_count();
  result.markers_per_level.assign(tree.MaxLevel() + 1, 0);
  tree.markers.clear();
  for (const int s : chosen) {
    const Site& site = placer.site(s);
    Marker m;
    m.id = static_cast<int>(tree.markers.size());
    m.label = fmt::format("M{}", m.id);
    m.branch = site.branch;
    m.arc_length = site.arc;
    m.position = tree.branches[site.branch].nodes[site.node].position;
    tree.markers.push_back(m);
    ++result.markers_per_level[tree.branches[site.branch].level];
    result.hidden += site.visible ? 0 : 1;
  }
  for (Marker& m : tree.markers) {
    m.parent = m.id == 0 ? -1 : NearestMarkerBelow(tree, tree.markers, m);
    if (m.id != 0 && m.parent < 0) m.parent = 0;
  }
  return result;
}

}  // namespace simtree::synth
