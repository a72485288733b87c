#pragma once
// Preprocessing of one view (paper III-A, "Preprocessing"): a raw camera-frame cloud to a clean
// tree cloud. Ground plane removal by RANSAC, statistical outlier removal, voxel-grid
// downsampling, and keeping the tree's cluster. The ground plane also gives the view's "up"
// direction, which registration uses to find the trunk.
//
// The paper removes outliers before the ground; here the ground goes first because it holds most
// of a view's points and the outlier filter costs a neighbour search per point. The effect on the
// tree is the same.

#include <cstdint>
#include <optional>
#include <string>

#include <open3d/geometry/PointCloud.h>
#include <Eigen/Core>

namespace simtree::preprocessing {

struct PreprocessOptions {
  // Ground: a RANSAC plane on a sample of the cloud, accepted when its normal is within
  // `max_ground_tilt_deg` of the camera's up (-y: the camera is held roughly level) and with the
  // fewest points below it (the scene stands on the ground). Points within
  // `ground_noise_sigmas` robust standard deviations of it (at least `min_ground_band_m`) and
  // below it are removed.
  bool remove_ground = true;            // find and remove the ground plane
  double ground_search_band_m = 0.05;   // m, half-width of a RANSAC plane's inlier band
  double ground_noise_sigmas = 3.0;     // ground noise sigmas removed above the plane
  double min_ground_band_m = 0.01;      // m, the least band removed above the plane
  double max_ground_tilt_deg = 30.0;    // deg, [0, 90]: the ground normal off the camera's -y
  int ground_ransac_iterations = 400;   // RANSAC planes tried, > 0
  size_t ground_sample_points = 20000;  // points the RANSAC scores planes on, > 0
  double min_ground_share = 0.05;       // [0, 1]: a plane holding less of the sample is no ground

  // Statistical outlier removal: a point whose mean distance to its `outlier_neighbors` nearest
  // neighbours exceeds the cloud's mean by `outlier_std_ratio` standard deviations goes.
  int outlier_neighbors = 16;      // neighbours per point, >= 0 (0: no outlier removal)
  double outlier_std_ratio = 2.0;  // standard deviations allowed, > 0

  // Voxel grid: `voxel_size_m`, or when 0, `voxel_spacing_factor` times the measured point
  // spacing of the tree points (the paper: 2-3 times).
  double voxel_size_m = 0.0;          // m, >= 0 (0: voxel_spacing_factor x point spacing)
  double voxel_spacing_factor = 2.5;  // point spacings, > 0

  // Tree cluster: connected components at `cluster_link_factor` voxels; the largest is the tree,
  // and smaller ones closer to it than `cluster_attach_distance_m` (twigs cut off by sensor
  // dropout) stay with it.
  bool keep_tree_cluster = true;            // drop the clusters away from the tree
  double cluster_link_factor = 3.0;         // voxels, > 0
  double cluster_attach_distance_m = 0.12;  // m, >= 0

  size_t min_tree_points = 100;  // fewer points off the ground: no tree in the view (an error)

  uint64_t seed = 1;  // of the RANSAC and of the spacing's sample

  // Throws InputError naming the field of a nonsense value (a negative size, a NaN...).
  void Validate() const;
};

struct GroundPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit, pointing to the camera's side (up)
  double offset = 0.0;                               // normal . x + offset = 0 on the plane
  double noise_m = 0.0;  // robust standard deviation of the ground points' residuals
  size_t points = 0;
  double SignedDistance(const Eigen::Vector3d& p) const { return normal.dot(p) + offset; }
};

struct PreprocessResult {
  open3d::geometry::PointCloud cloud;  // the tree, camera frame
  std::optional<GroundPlane> ground;
  // Up in the camera frame: the ground normal, or -y (a level camera) when no ground was found.
  Eigen::Vector3d up = -Eigen::Vector3d::UnitY();
  double point_spacing_m = 0.0;  // median nearest-neighbour distance of the tree points, measured
  double voxel_size_m = 0.0;     // the grid used
  size_t input_points = 0;
  size_t ground_points = 0;       // removed as ground (or below it)
  size_t outlier_points = 0;      // removed by the statistical filter
  size_t downsampled_points = 0;  // left after the voxel grid
  size_t off_tree_points = 0;     // removed with clusters other than the tree
  double seconds = 0.0;
  // Share of the non-ground points the voxel grid removed (the paper: 30-40%).
  double DownsampleRemovedShare() const;
};

// Throws InputError naming `source` when the cloud is empty, has non-finite points or nothing is
// left of it.
PreprocessResult PreprocessView(const open3d::geometry::PointCloud& camera_cloud,
                                const PreprocessOptions& options = {},
                                const std::string& source = "<memory>");

// The ground plane alone (nullopt when none is found): what PreprocessView uses.
std::optional<GroundPlane> FindGroundPlane(const open3d::geometry::PointCloud& camera_cloud,
                                           const PreprocessOptions& options = {});

}  // namespace simtree::preprocessing
