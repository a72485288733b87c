#include "simtree/reconstruction/detail/scan_graph.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <queue>
#include <tuple>
#include <unordered_map>

#include "simtree/core/option_checks.h"

namespace simtree::reconstruction {
namespace {

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int Find(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  bool Unite(int a, int b) {
    a = Find(a);
    b = Find(b);
    if (a == b) return false;
    parent_[std::max(a, b)] = std::min(a, b);
    return true;
  }

 private:
  std::vector<int> parent_;
};

struct Link {
  float length;
  int a, b;
  bool operator<(const Link& o) const {
    return std::tie(length, a, b) < std::tie(o.length, o.a, o.b);
  }
};

}  // namespace

void ScanGraphOptions::Validate() const {
  CheckPositive("neighbour_radius_m", neighbour_radius_m);
  CheckAtLeast("max_neighbours", max_neighbours, 1);
  CheckNonNegative("max_gap_m", max_gap_m);
  CheckAtLeast("min_piece_points", min_piece_points, 1);
}

ScanGraph BuildScanGraph(std::span<const Eigen::Vector3d> points, const PointIndex& index,
                         const ScanGraphOptions& options) {
  options.Validate();
  const int n = static_cast<int>(points.size());
  ScanGraph graph;
  // Nearest-neighbour relations are not symmetric: collect undirected links, once each.
  std::vector<Link> links;
  std::vector<int> near;
  std::vector<double> d2;
  for (int i = 0; i < n; ++i) {
    index.NearestWithin(points[i], options.neighbour_radius_m, options.max_neighbours + 1, near,
                        d2);
    for (size_t k = 0; k < near.size(); ++k) {
      if (near[k] == i) continue;
      links.push_back(
          {static_cast<float>(std::sqrt(d2[k])), std::min(i, near[k]), std::max(i, near[k])});
    }
  }
  std::sort(links.begin(), links.end(),
            [](const Link& x, const Link& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
  links.erase(std::unique(links.begin(), links.end(),
                          [](const Link& x, const Link& y) { return x.a == y.a && x.b == y.b; }),
              links.end());
  std::vector<std::vector<std::pair<int, float>>> adjacency(n);
  for (const Link& link : links) {
    adjacency[link.a].push_back({link.b, link.length});
    adjacency[link.b].push_back({link.a, link.length});
  }

  UnionFind pieces(n);
  for (int i = 0; i < n; ++i) {
    for (const auto& e : adjacency[i]) pieces.Unite(i, e.first);
  }
  graph.piece.resize(n);
  std::vector<int> piece_size(n, 0);
  for (int i = 0; i < n; ++i) ++piece_size[graph.piece[i] = pieces.Find(i)];
  graph.pieces = static_cast<int>(
      std::count_if(piece_size.begin(), piece_size.end(), [](int s) { return s > 0; }));

  if (options.max_gap_m > options.neighbour_radius_m && graph.pieces > 1) {
    // Bridges are searched between representatives, one point per piece per coarse voxel, so a
    // dense cloud costs no more than a sparse one; a bridge is at most a coarse voxel longer than
    // the true gap.
    const double coarse = std::max(options.neighbour_radius_m, options.max_gap_m / 8.0);
    std::unordered_map<uint64_t, int> representative_of;  // (voxel, piece) hash -> point
    std::vector<int> representatives;
    for (int i = 0; i < n; ++i) {
      const int own = graph.piece[i];
      if (piece_size[own] < options.min_piece_points) continue;
      const Eigen::Vector3d c = (points[i] / coarse).array().floor();
      uint64_t key = static_cast<uint64_t>(own);
      for (int axis = 0; axis < 3; ++axis) {
        key = key * 0x9E3779B97F4A7C15ull + static_cast<uint64_t>(static_cast<int64_t>(c[axis]));
      }
      if (representative_of.try_emplace(key, i).second) representatives.push_back(i);
    }
    std::vector<Eigen::Vector3d> positions(representatives.size());
    for (size_t k = 0; k < representatives.size(); ++k) positions[k] = points[representatives[k]];
    const PointIndex coarse_index(positions);
    const int largest = static_cast<int>(std::max_element(piece_size.begin(), piece_size.end()) -
                                         piece_size.begin());
    std::vector<Link> candidates;
    std::vector<int> seen_pieces;
    for (size_t k = 0; k < representatives.size(); ++k) {
      const int i = representatives[k];
      const int own = graph.piece[i];
      if (own == largest) continue;  // found from the other side
      coarse_index.WithinRadius(points[i], options.max_gap_m, near, d2);
      seen_pieces.clear();
      for (size_t m = 0; m < near.size(); ++m) {  // nearest first: keep the first per piece
        const int j = representatives[near[m]];
        const int other = graph.piece[j];
        if (other == own ||
            std::find(seen_pieces.begin(), seen_pieces.end(), other) != seen_pieces.end()) {
          continue;
        }
        seen_pieces.push_back(other);
        candidates.push_back({static_cast<float>(std::sqrt(d2[m])), i, j});
      }
    }
    // Kruskal on pieces: the shortest links that join two pieces not joined yet.
    std::sort(candidates.begin(), candidates.end());
    UnionFind joined(n);
    for (const Link& link : candidates) {
      if (!joined.Unite(graph.piece[link.a], graph.piece[link.b])) continue;
      adjacency[link.a].push_back({link.b, link.length});
      adjacency[link.b].push_back({link.a, link.length});
      ++graph.bridges;
      graph.longest_bridge_m = std::max(graph.longest_bridge_m, static_cast<double>(link.length));
    }
  }

  graph.offsets.assign(n + 1, 0);
  for (int i = 0; i < n; ++i) graph.offsets[i + 1] = graph.offsets[i] + adjacency[i].size();
  graph.targets.reserve(graph.offsets[n]);
  graph.lengths.reserve(graph.offsets[n]);
  for (int i = 0; i < n; ++i) {
    for (const auto& [j, length] : adjacency[i]) {
      graph.targets.push_back(j);
      graph.lengths.push_back(length);
    }
  }
  return graph;
}

GeodesicField GeodesicDistances(const ScanGraph& graph, std::span<const int> roots) {
  const int n = graph.size();
  GeodesicField field;
  field.distance.assign(n, std::numeric_limits<double>::infinity());
  field.predecessor.assign(n, -1);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (const int r : roots) {
    if (r < 0 || r >= n || field.distance[r] == 0.0) continue;
    field.distance[r] = 0.0;
    queue.push({0.0, r});
  }
  while (!queue.empty()) {
    const auto [d, i] = queue.top();
    queue.pop();
    if (d > field.distance[i]) continue;
    for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
      const int j = graph.targets[e];
      const double through = d + graph.lengths[e];
      if (through < field.distance[j]) {
        field.distance[j] = through;
        field.predecessor[j] = i;
        queue.push({through, j});
      }
    }
  }
  return field;
}

}  // namespace simtree::reconstruction
