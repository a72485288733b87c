#pragma once
// The trunk of a tree seen from one view and its first branching point, which centres the key
// region of the paper's coarse registration (III-A, Fig. 4a-b).
//
// The cloud is cut into thin slices across the up direction; each slice's points are grouped in
// the slice plane. The trunk starts as the largest group at the bottom and is followed upwards
// while each slice holds one group about as wide as the trunk below it. It ends where the slice
// splits into two or more substantial groups, or one group widens well beyond the trunk, and the
// split holds for a few slices: that is the first branching point. A side twig (a small group)
// does not end the trunk.

#include <optional>
#include <string>
#include <vector>

#include <open3d/geometry/PointCloud.h>
#include <Eigen/Core>

namespace simtree::registration {

struct TrunkOptions {
  double slice_height_m = 0.04;  // m, > 0: thickness of a slice across up
  // m, >= 0: points closer than this in the slice plane are one group (0: 3 times the
  // `spacing_m` given to FindTrunk, at least 2 cm).
  double link_distance_m = 0.0;
  double min_trunk_length_m = 0.25;  // m, >= 0: a shorter stem is no trunk
  double widen_factor = 1.8;  // > 0: a slice this many times wider than the trunk starts the crown
  double min_arm_share = 0.15;  // [0, 1]: of a slice's points, for a group to be a fork's arm
  int confirm_slices = 2;       // >= 0: slices after a split that must stay split
  int max_gap_slices = 2;       // >= 0: empty slices (occlusion) the trunk may cross

  // Throws InputError naming the field of a nonsense value.
  void Validate() const;
};

// A cylinder fitted to the trunk's points between its base and the branching point. One view sees
// only the camera's half of the trunk, whose centroid lies off the axis; the fitted axis does
// not, so two views' trunk axes coincide however far apart the views are.
struct TrunkCylinder {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // on the axis, at the middle of the fit
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit, upwards
  double radius_m = 0.0;
  double half_length_m = 0.0;  // the fit spans point +- half_length * axis
  double rms_m = 0.0;          // of the points' distances to the surface
  int points = 0;
};

struct TrunkFit {
  Eigen::Vector3d base = Eigen::Vector3d::Zero();          // lowest trunk point, on its axis
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();         // unit, upwards
  Eigen::Vector3d branch_point = Eigen::Vector3d::Zero();  // on the axis, where the crown starts
  double visible_width_m = 0.0;  // median width of the trunk's slices (about its diameter)
  double length_m = 0.0;         // base to branch point
  bool fork_found = false;       // false: the trunk ran to the top of the view without forking
  int slices = 0;
  std::optional<TrunkCylinder> cylinder;  // filled by FitTrunkCylinder when it succeeds
};

// Finds the trunk of `cloud` (camera frame) given `up` (unit, camera frame) and the cloud's point
// spacing. nullopt, with the reason in `why`, when no trunk is seen.
std::optional<TrunkFit> FindTrunk(const open3d::geometry::PointCloud& cloud,
                                  const Eigen::Vector3d& up, double spacing_m,
                                  const TrunkOptions& options = {}, std::string* why = nullptr);

struct CylinderFitOptions {
  double margin_m = 0.06;      // m, >= 0: left out above the base and below the branching point
  int iterations = 15;         // Gauss-Newton steps, >= 1
  double huber_m = 0.01;       // m, > 0: robust weights beyond this residual
  int min_points = 60;         // >= 5: fewer trunk points give no cylinder
  double min_length_m = 0.12;  // m, >= 0: a shorter stretch of trunk gives no cylinder

  // Throws InputError naming the field of a nonsense value.
  void Validate() const;
};

// The top of the trunk is cut off where the points stop fitting (a fork the slices did not catch:
// one arm hidden behind the other), and the rest refitted. nullopt when the trunk holds too few
// points or the fit does not converge to a plausible cylinder (radius within [0.3, 3] times half
// the visible width).
std::optional<TrunkCylinder> FitTrunkCylinder(const open3d::geometry::PointCloud& cloud,
                                              const TrunkFit& trunk,
                                              const CylinderFitOptions& options = {});

// The key region: the sphere around the first branching point.
struct KeyRegion {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius_m = 0.0;
};

struct KeyRegionOptions {
  // Radius: `radius_m`, or when 0, `height_share` of the tree's visible height, within
  // [min_radius_m, max_radius_m].
  double radius_m = 0.0;       // m, >= 0 (0: from the height)
  double height_share = 0.25;  // [0, 1] of the tree's visible height
  double min_radius_m = 0.35;  // m, >= 0
  double max_radius_m = 1.2;   // m, >= min_radius_m

  // Throws InputError naming the field of a nonsense value.
  void Validate() const;
};

KeyRegion KeyRegionOf(const TrunkFit& trunk, const open3d::geometry::PointCloud& cloud,
                      const Eigen::Vector3d& up, const KeyRegionOptions& options = {});

// Indices of the points of `cloud` inside `region`.
std::vector<size_t> PointsInside(const open3d::geometry::PointCloud& cloud,
                                 const KeyRegion& region);

}  // namespace simtree::registration
