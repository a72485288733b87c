#pragma once
// Where the virtual camera stands: the ring of hand-held views around the tree for the static
// scans, and the tripod for the pull test. Poses are world_from_camera with OpenCV camera axes
// (x right, y down, z forward), as in io/ground_truth.h.
//
// A person scanning a small tree walks around it at roughly even steps, holding the camera at
// chest height and aiming at the middle of the tree so all of it is in view; the steps, the
// distance, the height, the aim and the roll all wander a little. `ScanRigOptions` says by how
// much; `hard` widens the gaps between views (fewer views, uneven steps), the case where
// registration must bridge large angles.

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "simtree/core/tree.h"

namespace simtree::synth {

// The camera at `eye` looking at `target`, with `up` (world) pointing up in the image (so the
// image's y axis, which points down, is as close to -up as the view allows) and a roll about
// the viewing axis (radians, positive turns the image clockwise as seen by the camera). Throws
// InputError when eye and target coincide or the view is along `up`.
Eigen::Isometry3d LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                         const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ(), double roll = 0.0);

struct ScanRigOptions {
  int views = 10;
  // Mean step between views; 0: 360 / views.
  double step_deg = 0.0;
  // Each view's azimuth wanders this much (uniform, +-) around its even place.
  double azimuth_jitter_deg = 4.0;
  // Distance from the trunk axis: chosen so the whole tree height fits the vertical field of
  // view with a margin (`fit_margin`), then clamped to [min, max] and jittered (+- jitter).
  double min_distance_m = 1.5;
  double max_distance_m = 3.0;
  double distance_jitter_m = 0.15;
  double vertical_fov_deg = 65.0;
  double fit_margin = 1.1;
  // Camera height above the ground (uniform in the range).
  double min_height_m = 1.1;
  double max_height_m = 1.6;
  // Aim: at the tree's mid-height on its trunk axis, off by up to this (uniform, +-, in the
  // image plane), and roll up to this.
  double aim_jitter_deg = 3.0;
  double roll_jitter_deg = 2.0;

  // A harder set: 7 views with uneven steps (up to about 80 degrees apart).
  static ScanRigOptions Hard();
};

// The scan views on a ring around the trunk (its base at the origin, Z up), aimed at the middle
// of the crown, the first at a seeded random azimuth. Deterministic for a seed.
std::vector<Eigen::Isometry3d> ScanViewPoses(const Tree& tree, const ScanRigOptions& options,
                                             uint64_t seed);

struct PullCameraOptions {
  // The tripod stands this far from the trunk axis, on the side the rope pulls towards turned by
  // `side_angle_deg` (a camera right behind the rope sees the swing edge-on; one at 90 degrees sees
  // it broadside, as in the paper's Fig. 6), at `height_m`, aimed at the middle of the crown.
  double distance_m = 0.0;  // 0: fit the tree height, as for the scans, within [1.8, 3.2] m
  double side_angle_deg = 70.0;
  double height_m = 1.3;
};

// The fixed camera of the pull test. `pull_direction` is the horizontal direction the rope pulls
// the branch (world).
Eigen::Isometry3d PullCameraPose(const Tree& tree, const Eigen::Vector3d& pull_direction,
                                 const PullCameraOptions& options = {});

}  // namespace simtree::synth
