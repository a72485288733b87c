#pragma once
// A stand-in for `simtree synth`'s merged clouds while synth is being built: a true tree (the
// authors' demo trees, or a small procedural one made here) scanned the way an Azure Kinect sees
// it from about ten views around it, merged in the world frame.
//
// Per view: the tubes of the tree are sampled densely, a z-buffer keeps the surface nearest to
// the camera in each pixel (so back faces and occluded wood vanish and spacing is one point per
// pixel, about 6 mm at 2 m), wood thinner than about 1.5 pixels is missed (the sensor's mixed
// pixels are filtered), points get Gaussian noise along the viewing ray growing with the square of
// the distance (3 mm at 2 m) and a third of it across, a few leafy occluders hide parts of the
// view, stray outliers are added. A few gaps hidden in every view are cut from the merged cloud.
// It is a stand-in, not a sensor model: synth's virtual Kinect replaces it for the acceptance
// scores.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "simtree/core/tree.h"

namespace simtree::test {

struct StandInScanOptions {
  int views = 10;
  double camera_distance_m = 2.5;     // horizontal distance from the trunk
  double camera_height_share = 0.45;  // of the tree's height, above its base
  double focal_px = 350.0;            // a pixel spans depth / focal_px metres
  double noise_at_2m_m = 0.003;       // depth noise standard deviation at 2 m
  double lateral_noise_share = 0.33;
  double min_diameter_px = 1.5;  // thinner wood is not seen
  int occluders_per_view = 3;
  double occluder_radius_m = 0.1;
  int hidden_gaps = 3;  // gaps no view sees, cut from the merged cloud
  double hidden_gap_radius_m = 0.05;
  double outlier_share = 0.003;
  uint64_t seed = 1;
};

struct StandInScan {
  std::vector<Eigen::Vector3d> points;  // merged, world frame
  std::vector<Eigen::Vector3d> cameras;
  double mean_spacing_m = 0.0;  // pixel footprint at the mean depth
};

StandInScan ScanLikeAKinect(const Tree& tree, const StandInScanOptions& options = {});

// A small procedural tree (metres, Z up, base at the origin): a trunk of 2.5-3.5 m and three
// levels of branches with pipe-model radii, all from `seed`.
Tree MakeStandInTree(uint64_t seed);

}  // namespace simtree::test
