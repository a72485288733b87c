#include "simtree/reconstruction/detail/voxel_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace simtree::reconstruction {

std::vector<Eigen::Vector3d> VoxelAverage(std::span<const Eigen::Vector3d> points, double voxel) {
  std::vector<Eigen::Vector3d> out;
  if (points.empty() || !(voxel > 0)) return out;
  Eigen::Vector3d lo = points[0];
  for (const Eigen::Vector3d& p : points) lo = lo.cwiseMin(p);
  // 21 bits per axis: 2 million voxels along each, far more than any tree needs.
  std::vector<std::pair<uint64_t, uint32_t>> keys(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d c = ((points[i] - lo) / voxel).array().floor();
    const uint64_t x = std::min<uint64_t>(static_cast<uint64_t>(c.x()), (1u << 21) - 1);
    const uint64_t y = std::min<uint64_t>(static_cast<uint64_t>(c.y()), (1u << 21) - 1);
    const uint64_t z = std::min<uint64_t>(static_cast<uint64_t>(c.z()), (1u << 21) - 1);
    keys[i] = {(x << 42) | (y << 21) | z, static_cast<uint32_t>(i)};
  }
  std::sort(keys.begin(), keys.end());
  for (size_t begin = 0; begin < keys.size();) {
    size_t end = begin;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    while (end < keys.size() && keys[end].first == keys[begin].first)
      sum += points[keys[end++].second];
    out.push_back(sum / static_cast<double>(end - begin));
    begin = end;
  }
  return out;
}

std::vector<Eigen::Vector3d> VoxelAverageAtMost(std::span<const Eigen::Vector3d> points,
                                                size_t max_points, double* voxel) {
  std::vector<Eigen::Vector3d> out = VoxelAverage(points, *voxel);
  for (int round = 0; round < 6 && out.size() > max_points; ++round) {
    // A surface's voxel count falls with the square of the voxel.
    *voxel *= 1.05 * std::sqrt(static_cast<double>(out.size()) / max_points);
    out = VoxelAverage(points, *voxel);
  }
  return out;
}

}  // namespace simtree::reconstruction
