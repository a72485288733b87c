#pragma once
// A STAND-IN for `simtree synth` scan views, used until synth lands on main: a capture folder
// (scans/view_XX/{color.png, depth.png, intrinsics.json}, gt/scan_poses.json, gt/tree.json) of a
// known tree, or point-cloud views cut from a real laser scan, each in its camera frame with its
// true pose known. It is deliberately simple and is not the sensor model of issue 4:
// - cameras on a ring 2-3 m from the trunk, every `angle_step_deg`, height and aim jittered;
// - a z-buffer over the tree's branch segments (capsules) and a ground plane, so the tree
//   occludes itself and the ground; nothing beyond the range;
// - branches narrower than ~1.5 px vanish; depth noise sigma(z) = a + b z^2, 1 mm quantisation;
//   flying pixels at silhouettes; sparse outliers; small branch sway between views.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <open3d/geometry/PointCloud.h>
#include <Eigen/Geometry>

#include "simtree/core/tree.h"
#include "simtree/io/capture.h"
#include "simtree/io/ground_truth.h"

namespace simtree::test {

struct StandInOptions {
  int views = 10;
  double angle_step_deg = 36.0;
  double first_angle_deg = -1.0;  // < 0: drawn from the seed
  double min_distance_m = 2.2;    // camera to trunk, horizontally
  double max_distance_m = 3.2;
  double camera_height_m = 1.3;
  double height_jitter_m = 0.2;
  double aim_height_fraction = 0.45;  // aim at this share of the tree's height on its axis
  double aim_jitter_deg = 3.0;
  double roll_jitter_deg = 2.0;
  double min_range_m = 0.5;
  double max_range_m = 3.86;
  double noise_a_m = 0.0015;  // depth noise standard deviation a + b z^2
  double noise_b_per_m = 0.0010;
  double min_pixel_width = 1.5;
  double flying_pixel_rate = 0.3;  // share of silhouette pixels given an in-between depth
  double outlier_rate = 0.002;     // share of all pixels given a random depth
  double sway_m = 0.003;           // per branch level, between views
  bool ground = true;
  uint64_t seed = 1;
};

// Azure Kinect NFOV unbinned-like intrinsics: 640x576, f = 504 px.
CameraIntrinsics StandInIntrinsics();

// The tree of an authors' demo file in metres, Z up, its trunk base moved to the origin, scaled
// to `height_m` tall, radii scaled as much again times `radius_scale` (the demo trees are stout:
// 0.5 gives a 3 m tree a trunk of about 13 cm, like the paper's young trees).
Tree LoadDemoTree(const std::filesystem::path& path, double height_m = 3.0,
                  double radius_scale = 0.5);

// Camera poses on the ring around a tree of height `tree_height_m` standing at the origin.
std::vector<ViewPose> StandInPoses(double tree_height_m, const StandInOptions& options);

// One view of `tree` (world frame) from `world_from_camera`.
RgbdImage RenderStandInView(const Tree& tree, const Eigen::Isometry3d& world_from_camera,
                            const StandInOptions& options, uint64_t view_seed);

// Writes a whole capture folder at `root` (replacing it) and returns the true poses.
std::vector<ViewPose> WriteStandInCapture(const Tree& tree, const StandInOptions& options,
                                          const std::filesystem::path& root);

// A real laser scan (world frame, Z up) moved so its trunk base is at the origin and its lowest
// point at z = 0.
open3d::geometry::PointCloud LoadRealScan(const std::filesystem::path& path);

// One view of a real scan: points in the field of view and range, hidden points removed
// (Katz et al.), noise along the ray, outliers and ground points added; camera frame.
open3d::geometry::PointCloud CutStandInView(const open3d::geometry::PointCloud& scan,
                                            const Eigen::Isometry3d& world_from_camera,
                                            const StandInOptions& options, uint64_t view_seed);

}  // namespace simtree::test
