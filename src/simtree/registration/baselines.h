#pragma once
// The registration methods a user might pick instead of ours, for side-by-side comparisons
// (bench/registration_compare.cc): the paper's PCA-ICP (Table II), and Open3D's FPFH-RANSAC
// followed by its point-to-plane ICP. (F-4PCS-ICP needs PCL, which only bench/ links.) Each takes
// the same preprocessed views (camera frame, camera-oriented normals) and computes everything it
// needs itself, so its time is the whole pair's.

#include <string>
#include <vector>

#include <open3d/geometry/PointCloud.h>
#include <Eigen/Geometry>

namespace simtree::registration {

struct BaselineResult {
  Eigen::Isometry3d target_from_source = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d coarse = Eigen::Isometry3d::Identity();  // before ICP
  double coarse_seconds = 0.0;
  double seconds = 0.0;  // features + coarse + ICP
  double fitness = 0.0;  // Open3D's: share of source points with a correspondence
};

struct BaselineOptions {
  double spacing_m = 0.01;  // m, > 0: the clouds' point spacing; distances are multiples of it
  double feature_voxel_factor = 2.0;    // point spacings, > 0: the FPFH clouds' voxel grid
  double normal_radius_factor = 2.0;    // feature voxels, > 0: the FPFH clouds' normals
  double feature_radius_factor = 5.0;   // feature voxels, > 0: the FPFH radius
  double ransac_distance_factor = 1.5;  // feature voxels, > 0: RANSAC's inlier distance
  int ransac_iterations = 100000;       // >= 1
  double ransac_confidence = 0.999;     // [0, 1]
  // Point spacings, each > 0, largest first: Open3D point-to-plane ICP's distances (empty: none).
  std::vector<double> icp_distance_factors = {6.0, 3.0, 1.5};
  int icp_iterations = 30;  // >= 1, per distance
  int seed = 1;             // of RANSAC

  // Throws InputError naming the field of a nonsense value.
  void Validate() const;
};

// PCA-ICP: centroids and principal axes aligned (of the four proper sign choices of the axes,
// the one whose ICP overlaps most), then Open3D's point-to-plane ICP.
BaselineResult PcaIcp(const open3d::geometry::PointCloud& source,
                      const open3d::geometry::PointCloud& target, const BaselineOptions& options);

// Open3D: FPFH on voxel-downsampled clouds, RANSAC on feature matches (mutual filter, edge-length
// and distance checkers), then its point-to-plane ICP.
BaselineResult Open3dFpfhRansacIcp(const open3d::geometry::PointCloud& source,
                                   const open3d::geometry::PointCloud& target,
                                   const BaselineOptions& options);

// Open3D's point-to-plane ICP from `initial`, coarse to fine (the ICP the baselines share).
Eigen::Isometry3d Open3dIcp(const open3d::geometry::PointCloud& source,
                            const open3d::geometry::PointCloud& target,
                            const Eigen::Isometry3d& initial, const BaselineOptions& options,
                            double* fitness = nullptr);

}  // namespace simtree::registration
