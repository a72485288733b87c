#pragma once
// Points averaged per cubic voxel: the working resolution of a reconstruction. Sorting by voxel
// key rather than hashing keeps it fast on a few hundred thousand points and its output order
// deterministic (voxels in key order).

#include <span>
#include <vector>

#include <Eigen/Core>

namespace simtree::reconstruction {

// The mean of the points in each occupied voxel of edge `voxel` (metres, > 0).
std::vector<Eigen::Vector3d> VoxelAverage(std::span<const Eigen::Vector3d> points, double voxel);

// Averaged at `*voxel`, or at a coarser voxel (written back) when that leaves more than
// `max_points`.
std::vector<Eigen::Vector3d> VoxelAverageAtMost(std::span<const Eigen::Vector3d> points,
                                                size_t max_points, double* voxel);

}  // namespace simtree::reconstruction
