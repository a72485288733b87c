#include "simtree/reconstruction/detail/scene_cleanup.h"

#include <algorithm>
#include <numeric>

#include <tbb/parallel_for.h>

#include "simtree/core/option_checks.h"
#include "simtree/reconstruction/detail/point_index.h"

namespace simtree::reconstruction {
namespace {

int FindRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

}  // namespace

void SparseReturnOptions::Validate() const {
  CheckPositive("radius_m", radius_m);
  CheckAtLeast("min_neighbours", min_neighbours, 0);
}

void GroundObjectOptions::Validate() const {
  CheckPositive("neighbour_radius_m", neighbour_radius_m);
  CheckNonNegative("touch_height_m", touch_height_m);
}

std::vector<char> FindSparseReturns(std::span<const Eigen::Vector3d> points,
                                    const SparseReturnOptions& options) {
  options.Validate();
  std::vector<char> sparse(points.size(), 0);
  if (points.empty()) return sparse;
  const PointIndex index(points);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, points.size(), 1024),
                    [&](const tbb::blocked_range<size_t>& range) {
                      std::vector<int> found;
                      std::vector<double> squared;
                      for (size_t i = range.begin(); i < range.end(); ++i) {
                        // The point finds itself too.
                        index.NearestWithin(points[i], options.radius_m, options.min_neighbours + 1,
                                            found, squared);
                        sparse[i] = static_cast<int>(found.size()) < options.min_neighbours + 1;
                      }
                    });
  return sparse;
}

std::vector<char> FindObjectsOnGround(std::span<const Eigen::Vector3d> points,
                                      const GroundPlane& ground,
                                      const GroundObjectOptions& options) {
  options.Validate();
  std::vector<char> object(points.size(), 0);
  if (points.empty() || !ground.found) return object;
  const PointIndex index(points);
  std::vector<int> parent(points.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<int> found;
  std::vector<double> squared;
  for (size_t i = 0; i < points.size(); ++i) {
    index.NearestWithin(points[i], options.neighbour_radius_m, 10, found, squared);
    for (const int j : found) {
      const int a = FindRoot(parent, static_cast<int>(i)), b = FindRoot(parent, j);
      if (a != b) parent[a] = b;
    }
  }
  std::vector<int> size(points.size(), 0);
  std::vector<char> touches(points.size(), 0);
  for (size_t i = 0; i < points.size(); ++i) {
    const int r = FindRoot(parent, static_cast<int>(i));
    ++size[r];
    if (ground.HeightAbove(points[i]) <= ground.clearance_m + options.touch_height_m) {
      touches[r] = 1;
    }
  }
  int tree = -1;
  for (size_t r = 0; r < points.size(); ++r) {
    if (touches[r] && (tree < 0 || size[r] > size[tree])) tree = static_cast<int>(r);
  }
  for (size_t i = 0; i < points.size(); ++i) {
    const int r = FindRoot(parent, static_cast<int>(i));
    object[i] = touches[r] && r != tree;
  }
  return object;
}

}  // namespace simtree::reconstruction
