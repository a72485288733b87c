#pragma once
// Markers placed on a static tree by position: each marker's rest position (from its trajectory,
// camera frame) is taken to the world by the pull camera's pose and put on the nearest branch
// (nearest point of the branch's polyline; thin twigs near a thick branch lose to it only when
// the marker is outside the twig's radius by more than the thick branch's). The links of the
// simplified tree (paper Fig. 8) then follow the tree: a marker's parent is the next marker down
// the hierarchy (nearer the base on its own branch, else on the nearest ancestor branch, nearest
// the attachment from below).

#include <vector>

#include <Eigen/Geometry>

#include "simtree/core/tree.h"
#include "simtree/io/capture.h"
#include "simtree/io/trajectories.h"

namespace simtree::identification {

struct MarkerPlacement {
  int marker = 0;
  int branch = -1;          // -1 when the marker never has a valid position
  double arc_length = 0.0;  // metres from the branch base
  double distance_m = 0.0;  // from the marker to the branch surface (0 inside it)
  Eigen::Vector3d rest_world = Eigen::Vector3d::Zero();
};

// The rest position of every track: the mean over the last `rest_fraction` of its valid frames.
std::vector<Eigen::Vector3d> RestPositions(const Trajectories& trajectories,
                                           double rest_fraction = 0.25);

// One placement per track of `trajectories`, in track order.
std::vector<MarkerPlacement> PlaceMarkersOnTree(const Tree& tree, const Trajectories& trajectories,
                                                const Eigen::Isometry3d& world_from_camera);

// The marker list with links that follow the tree, labels "M<id>", branches set. Markers with no
// branch are left out. The root is the marker nearest the trunk base along the hierarchy; when
// several markers have no ancestor marker, the others link to it.
std::vector<MarkerLink> LinkMarkersByTree(const Tree& tree,
                                          const std::vector<MarkerPlacement>& placements);

// The marker list `identify` works with when a static tree is given: `listed` (markers.json;
// empty when there is none) with each marker's branch filled in from its placement where the list
// gives none, or, when nothing is listed, links that follow the tree (LinkMarkersByTree). Warns of
// markers placed farther than `max_distance_m` from their branch (a wrong camera pose, most
// likely).
struct TreeMarkers {
  std::vector<MarkerLink> markers;
  std::vector<MarkerPlacement> placements;  // one per track, in track order
};
TreeMarkers MarkersOnTree(const Tree& tree, const Trajectories& trajectories,
                          const Eigen::Isometry3d& world_from_camera,
                          std::vector<MarkerLink> listed, double max_distance_m = 0.05);

}  // namespace simtree::identification
