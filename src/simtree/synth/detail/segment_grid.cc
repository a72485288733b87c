#include "simtree/synth/detail/segment_grid.h"

#include <algorithm>
#include <cmath>

namespace simtree::synth {

double SegmentDistance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                       const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  // Minimise |p0 + s u - (q0 + t v)| over s, t in [0, 1]: solve the unconstrained 2x2 system,
  // clamp s, recompute t for it, clamp t, recompute s (exact for convex segment pairs).
  const Eigen::Vector3d u = p1 - p0, v = q1 - q0, w = p0 - q0;
  const double a = u.dot(u), b = u.dot(v), c = v.dot(v), d = u.dot(w), e = v.dot(w);
  constexpr double kTiny = 1e-18;
  double s = 0.0, t = 0.0;
  if (a <= kTiny && c <= kTiny) return w.norm();
  if (a <= kTiny) {
    t = std::clamp(e / c, 0.0, 1.0);
  } else if (c <= kTiny) {
    s = std::clamp(-d / a, 0.0, 1.0);
  } else {
    const double denom = a * c - b * b;
    s = denom > kTiny * a * c ? std::clamp((b * e - c * d) / denom, 0.0, 1.0) : 0.0;
    t = (b * s + e) / c;
    if (t < 0.0) {
      t = 0.0;
      s = std::clamp(-d / a, 0.0, 1.0);
    } else if (t > 1.0) {
      t = 1.0;
      s = std::clamp((b - d) / a, 0.0, 1.0);
    }
  }
  return (w + s * u - t * v).norm();
}

SegmentGrid::SegmentGrid(double cell_size) : cell_size_(cell_size) {}

SegmentGrid::Key SegmentGrid::CellKey(int x, int y, int z) const {
  // 21 bits per axis: +-10^6 cells, far beyond any tree.
  constexpr int64_t kBias = 1 << 20;
  return ((x + kBias) << 42) | ((y + kBias) << 21) | (z + kBias);
}

Eigen::Vector3i SegmentGrid::Cell(const Eigen::Vector3d& p) const {
  return (p / cell_size_).array().floor().cast<int>();
}

void SegmentGrid::Add(const GridSegment& segment) {
  const int id = size();
  segments_.push_back(segment);
  visited_stamp_.push_back(0);
  max_radius_ = std::max(max_radius_, segment.radius);
  const Eigen::Vector3i lo = Cell(segment.a.cwiseMin(segment.b));
  const Eigen::Vector3i hi = Cell(segment.a.cwiseMax(segment.b));
  for (int x = lo.x(); x <= hi.x(); ++x) {
    for (int y = lo.y(); y <= hi.y(); ++y) {
      for (int z = lo.z(); z <= hi.z(); ++z) cells_[CellKey(x, y, z)].push_back(id);
    }
  }
}

bool SegmentGrid::AnyNear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double margin,
                          const std::function<bool(const GridSegment&)>& visit) const {
  if (++stamp_ == 0) {  // wrapped: forget every old stamp
    std::fill(visited_stamp_.begin(), visited_stamp_.end(), 0);
    stamp_ = 1;
  }
  const Eigen::Vector3d grow = Eigen::Vector3d::Constant(margin);
  const Eigen::Vector3i lo = Cell(a.cwiseMin(b) - grow);
  const Eigen::Vector3i hi = Cell(a.cwiseMax(b) + grow);
  for (int x = lo.x(); x <= hi.x(); ++x) {
    for (int y = lo.y(); y <= hi.y(); ++y) {
      for (int z = lo.z(); z <= hi.z(); ++z) {
        const auto it = cells_.find(CellKey(x, y, z));
        if (it == cells_.end()) continue;
        for (const int id : it->second) {
          if (visited_stamp_[id] == stamp_) continue;
          visited_stamp_[id] = stamp_;
          if (visit(segments_[id])) return true;
        }
      }
    }
  }
  return false;
}

}  // namespace simtree::synth
