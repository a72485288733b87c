#pragma once
// The neighbourhood graph of a scan and the geodesic distance of every point from the tree's base
// along it. A scanned tree falls apart into pieces wherever something hid it from every camera;
// the graph bridges such occlusion gaps (up to a length) with the shortest links between pieces,
// chosen like the edges of a minimum spanning tree, so distances run through the whole tree.

#include <span>
#include <vector>

#include <Eigen/Core>

#include "simtree/reconstruction/detail/point_index.h"

namespace simtree::reconstruction {

struct ScanGraphOptions {
  double neighbour_radius_m = 0.02;  // metres: points closer than this are linked
  int max_neighbours = 10;           // links per point (to the nearest ones)
  double max_gap_m = 0.2;            // metres, the longest occlusion gap bridged (0: none)
  int min_piece_points = 4;          // smaller pieces are outliers: never bridged

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

struct ScanGraph {
  // Adjacency in compressed rows: the neighbours of point i are targets[offsets[i]..offsets[i+1]).
  std::vector<int> offsets;
  std::vector<int> targets;
  std::vector<float> lengths;  // metres, per target
  std::vector<int> piece;      // per point: its connected piece before bridging
  int pieces = 0;
  int bridges = 0;  // gap links added
  double longest_bridge_m = 0.0;

  int size() const { return offsets.empty() ? 0 : static_cast<int>(offsets.size()) - 1; }
};

// `index` must be built over `points`.
ScanGraph BuildScanGraph(std::span<const Eigen::Vector3d> points, const PointIndex& index,
                         const ScanGraphOptions& options);

struct GeodesicField {
  std::vector<double> distance;  // metres from the nearest root; +inf when unreachable
  std::vector<int> predecessor;  // previous point on the shortest path; -1 for roots/unreached
};

// Dijkstra from every point in `roots` at once.
GeodesicField GeodesicDistances(const ScanGraph& graph, std::span<const int> roots);

}  // namespace simtree::reconstruction
