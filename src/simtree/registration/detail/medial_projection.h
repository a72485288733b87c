#pragma once
// Moves surface points seen from one side onto the axes of their branches, before the skeleton.
//
// One view sees only the camera's half of a branch. The L1 median of a half cylinder lies between
// the surface and the axis, on the camera's side, so skeletons of one branch from opposite views
// are a trunk radius or more apart: on a 10 cm trunk, further than the coarse alignment can
// tolerate. On a cylinder, every surface normal line passes through the axis; the point nearest
// (in least squares) to the normal lines of a point's neighbours is therefore its axis point. Each
// point moves there, at most `max_shift_m`, and only inwards (against its camera-facing normal).

#include <vector>

#include <open3d/geometry/KDTreeFlann.h>
#include <open3d/geometry/PointCloud.h>
#include <Eigen/Core>

namespace simtree::registration {

struct MedialProjectionOptions {
  double neighbourhood_m = 0.08;  // m, > 0: radius of the neighbourhood whose normal lines meet
  int max_neighbours = 40;        // >= 2: neighbours whose normal lines are used
  double max_shift_m =
      0.15;  // m, >= 0: no point moves further (about the thickest branch's radius)
  // >= 0, relative to the neighbour count: the pull towards the point itself, which keeps flat
  // patches (whose normal lines are parallel and meet nowhere) in place.
  double regularisation = 0.005;
  // A branch narrower than the neighbourhood is long (across its axis at most
  // `silhouette_elongation` of the extent along it, and the points on both its edges, in the
  // cross-section at the point, within `silhouette_containment` of the neighbourhood's reach
  // from it, so that they are the branch's edges and not where the neighbourhood ends) takes
  // its axis point from its silhouette: the width across the axis and the line of sight, which one
  // view sees whole, gives the radius r and the axis's place across; the axis lies r behind the
  // surface point there, less for a point off the middle (a circle). The normal lines' meeting
  // point lags on such branches: normals averaged over a neighbourhood wider than the branch turn
  // towards the camera, so their lines barely meet and the pull towards the point itself wins.
  // Needs the camera at the cloud's origin. False: the normal lines everywhere.
  bool silhouette = false;
  double silhouette_elongation = 0.5;   // > 0: width over length of a branch's neighbourhood
  double silhouette_containment = 0.6;  // [0, 1] of the neighbourhood's radius
  int silhouette_max_neighbours = 120;  // >= 2: neighbours the silhouette is measured on

  // Throws InputError naming the field of a nonsense value.
  void Validate() const;
};

// The projected positions of `indices` of `cloud` (which needs normals oriented to the camera);
// `tree` indexes `cloud`.
std::vector<Eigen::Vector3d> ProjectToMedialAxes(const open3d::geometry::PointCloud& cloud,
                                                 const open3d::geometry::KDTreeFlann& tree,
                                                 const std::vector<size_t>& indices,
                                                 const MedialProjectionOptions& options = {});

}  // namespace simtree::registration
