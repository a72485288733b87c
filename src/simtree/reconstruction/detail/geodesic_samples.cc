#include "simtree/reconstruction/detail/geodesic_samples.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "simtree/core/option_checks.h"

namespace simtree::reconstruction {
namespace {

int FindRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// Per point: its band (geodesic distance over the band width), -1 when unreached.
std::vector<int> BandOfEachPoint(const GeodesicField& field, double band_width_m) {
  std::vector<int> band(field.distance.size(), -1);
  for (size_t i = 0; i < band.size(); ++i) {
    if (std::isfinite(field.distance[i])) {
      band[i] = static_cast<int>(field.distance[i] / band_width_m);
    }
  }
  return band;
}

// The pieces of every band as a union-find forest over the points: points of one band joined by
// the graph's links inside the band.
std::vector<int> JoinPiecesOfBands(const ScanGraph& graph, std::span<const int> band) {
  const int n = static_cast<int>(band.size());
  std::vector<int> root(n);
  std::iota(root.begin(), root.end(), 0);
  for (int i = 0; i < n; ++i) {
    if (band[i] < 0) continue;
    for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
      const int j = graph.targets[e];
      if (j > i && band[j] == band[i]) {
        const int a = FindRoot(root, i), b = FindRoot(root, j);
        if (a != b) root[std::max(a, b)] = std::min(a, b);
      }
    }
  }
  return root;
}

// Joins, in `root`, the pieces of one band whose centroids are closer than merge_per_spread times
// the sum of their spreads: the arcs a ring breaks into. Returns how many were merged.
int MergeArcsIntoRings(std::span<const Eigen::Vector3d> points, std::span<const int> band,
                       std::vector<int>& root, const GeodesicSampleOptions& options) {
  struct Piece {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double sum2 = 0.0;
    int points = 0;
    int band = 0;
  };
  std::unordered_map<int, Piece> pieces;
  for (size_t i = 0; i < points.size(); ++i) {
    if (band[i] < 0) continue;
    Piece& piece = pieces[FindRoot(root, static_cast<int>(i))];
    piece.sum += points[i];
    piece.sum2 += points[i].squaredNorm();
    ++piece.points;
    piece.band = band[i];
  }
  std::unordered_map<int, std::vector<int>> pieces_of_band;
  for (const auto& [id, piece] : pieces) pieces_of_band[piece.band].push_back(id);
  int merged = 0;
  for (auto& [b, ids] : pieces_of_band) {
    std::erase_if(ids, [&](int id) { return pieces[id].points < options.min_points; });
    if (ids.size() < 2) continue;
    std::sort(ids.begin(), ids.end());  // deterministic
    auto centre = [&](int id) { return Eigen::Vector3d(pieces[id].sum / pieces[id].points); };
    auto spread = [&](int id) {
      const Piece& p = pieces[id];
      const Eigen::Vector3d c = p.sum / p.points;
      return std::sqrt(std::max(0.0, p.sum2 / p.points - c.squaredNorm()));
    };
    for (size_t x = 0; x < ids.size(); ++x) {
      for (size_t y = x + 1; y < ids.size(); ++y) {
        const double apart = (centre(ids[x]) - centre(ids[y])).norm();
        if (apart >= options.merge_per_spread * (spread(ids[x]) + spread(ids[y]))) continue;
        const int a = FindRoot(root, ids[x]), c = FindRoot(root, ids[y]);
        if (a != c) {
          root[std::max(a, c)] = std::min(a, c);
          ++merged;
        }
      }
    }
  }
  return merged;
}

// One sample per piece, numbered in order of the piece's lowest point index (deterministic):
// centroid, mean geodesic, spread, and as parent the sample its point nearest the base was
// reached from.
void SampleEachPiece(std::span<const Eigen::Vector3d> points, const GeodesicField& field,
                     std::span<const int> band, std::vector<int>& root, GeodesicSampling& out) {
  std::unordered_map<int, int> sample_of_root;
  std::vector<int> lowest_point;  // per sample: its point nearest the base
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    if (band[i] < 0) continue;
    const int r = FindRoot(root, i);
    auto [it, added] = sample_of_root.try_emplace(r, static_cast<int>(out.samples.size()));
    if (added) {
      out.samples.push_back({});
      out.samples.back().band = band[i];
      lowest_point.push_back(i);
    }
    const int s = it->second;
    GeodesicSample& sample = out.samples[s];
    sample.position += points[i];
    sample.geodesic_m += field.distance[i];
    ++sample.points;
    if (field.distance[i] < field.distance[lowest_point[s]]) lowest_point[s] = i;
    out.sample_of_point[i] = s;
  }
  for (GeodesicSample& sample : out.samples) {
    sample.position /= sample.points;
    sample.geodesic_m /= sample.points;
  }
  std::vector<double> spread2(out.samples.size(), 0.0);
  for (size_t i = 0; i < points.size(); ++i) {
    const int s = out.sample_of_point[i];
    if (s >= 0) spread2[s] += (points[i] - out.samples[s].position).squaredNorm();
  }
  for (size_t s = 0; s < out.samples.size(); ++s) {
    out.samples[s].spread_m = std::sqrt(spread2[s] / out.samples[s].points);
    const int before = field.predecessor[lowest_point[s]];
    out.samples[s].parent = before >= 0 ? out.sample_of_point[before] : -1;
  }
}

// Drops the samples of tiny pieces (stray points): their points count as dropped, their
// children re-hang on the dropped sample's nearest kept ancestor.
void DropSmallSamples(int min_points, GeodesicSampling& out) {
  std::vector<int> kept_index(out.samples.size(), -1);
  std::vector<GeodesicSample> kept;
  for (size_t s = 0; s < out.samples.size(); ++s) {
    if (out.samples[s].points >= min_points) {
      kept_index[s] = static_cast<int>(kept.size());
      kept.push_back(out.samples[s]);
    }
  }
  // A parent's base point is nearer the base than its child's, so walking up always ends.
  auto kept_ancestor = [&](int s) {
    while (s >= 0 && kept_index[s] < 0) s = out.samples[s].parent;
    return s >= 0 ? kept_index[s] : -1;
  };
  for (size_t s = 0; s < out.samples.size(); ++s) {
    if (kept_index[s] < 0) continue;
    kept[kept_index[s]].parent = kept_ancestor(out.samples[s].parent);
  }
  for (int& s : out.sample_of_point) {
    if (s < 0) continue;
    if (kept_index[s] < 0) ++out.dropped_points;
    s = kept_index[s];
  }
  out.samples = std::move(kept);
}

}  // namespace

void GeodesicSampleOptions::Validate() const {
  CheckPositive("band_width_m", band_width_m);
  CheckAtLeast("min_points", min_points, 1);
  CheckNonNegative("merge_per_spread", merge_per_spread);
}

GeodesicSampling SampleGeodesicBands(std::span<const Eigen::Vector3d> points,
                                     const ScanGraph& graph, const GeodesicField& field,
                                     const GeodesicSampleOptions& options) {
  options.Validate();
  GeodesicSampling out;
  out.sample_of_point.assign(points.size(), -1);
  const std::vector<int> band = BandOfEachPoint(field, options.band_width_m);
  out.unreached_points = static_cast<size_t>(std::count(band.begin(), band.end(), -1));
  std::vector<int> root = JoinPiecesOfBands(graph, band);
  if (options.merge_per_spread > 0.0) {
    out.merged_pieces = MergeArcsIntoRings(points, band, root, options);
  }
  SampleEachPiece(points, field, band, root, out);
  DropSmallSamples(options.min_points, out);
  return out;
}

}  // namespace simtree::reconstruction
