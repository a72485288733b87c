#pragma once
// A spatial hash of line segments (branch pieces with a radius): which stored segments come near
// a query segment. The tree generator uses it to keep new branches clear of existing ones, and
// marker placement to tell whether a branch hides a marker from the camera.

#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

namespace simtree::synth {

// Closest distance between segments [p0, p1] and [q0, q1] (either may be a point).
double SegmentDistance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                       const Eigen::Vector3d& q0, const Eigen::Vector3d& q1);

struct GridSegment {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  double radius = 0.0;
  int branch = -1;
  int index = 0;  // segment index on its branch (from node index to index + 1)
};

class SegmentGrid {
 public:
  // `cell_size` (metres) about the length of the stored segments.
  explicit SegmentGrid(double cell_size = 0.1);

  void Add(const GridSegment& segment);
  int size() const { return static_cast<int>(segments_.size()); }
  const GridSegment& segment(int i) const { return segments_[i]; }
  double max_radius() const { return max_radius_; }

  // Calls `visit` once for every stored segment whose bounding box, grown by `margin`, meets the
  // query segment's; it stops early when `visit` returns true and then returns true.
  bool AnyNear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double margin,
               const std::function<bool(const GridSegment&)>& visit) const;

 private:
  using Key = int64_t;
  Key CellKey(int x, int y, int z) const;
  Eigen::Vector3i Cell(const Eigen::Vector3d& p) const;

  double cell_size_;
  double max_radius_ = 0.0;
  std::vector<GridSegment> segments_;
  std::unordered_map<Key, std::vector<int>> cells_;
  mutable std::vector<uint32_t> visited_stamp_;
  mutable uint32_t stamp_ = 0;
};

}  // namespace simtree::synth
