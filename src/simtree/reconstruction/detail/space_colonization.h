#pragma once
// Space colonization (Runions, Lane and Prusinkiewicz 2007) grown through a scan: the attraction
// points are (samples of) the scanned points, and the skeleton grows from the trunk base towards
// them in steps until every point it can reach has been reached.
//
// One iteration: every live attraction point picks the nearest node that perceives it (within the
// influence radius, inside the node's perception cone, and, with geodesics, consistent with where
// the node is along the tree); every node picked by some points grows one new node one step
// towards the mean direction of its points; points within the kill radius of a node are reached
// and retire. A node picked again later grows a second child: that is how forks appear.
//
// Improvements for scans, each switchable so their effect can be measured
// (docs/reconstruction.md has the ablation):
//  - perception cone: a node sees only ahead of itself, so the skeleton does not grow backwards
//    into points it has passed;
//  - direction smoothing: a growing tip keeps part of its previous direction, which damps the
//    zigzag that noisy attraction points cause;
//  - thickness-scaled radii: a point standing for a thick piece of wood is perceived and reached
//    from further away, so the sides of a trunk do not sprout twigs;
//  - geodesic consistency: a node perceives a point only when the distance along the scan from
//    the node to it is about the straight distance (and reaches only such points), so a branch
//    does not jump to, or eat the points of, a neighbouring branch that passes close by;
//  - gap bridging: when growth stops, each group of points still unreached grows a bridge from the
//    nearest node if the gap is short enough (parts of the tree hidden from every camera);
//  - recentring: nodes end on the centre of the points they reached.

#include <span>

#include <Eigen/Core>

#include "simtree/reconstruction/detail/skeleton.h"

namespace simtree::reconstruction {

struct AttractionPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double weight = 1.0;       // scan points it stands for
  double thickness_m = 0.0;  // spread of those points around it: a radius hint
  double geodesic_m = -1.0;  // distance from the base along the scan; < 0 when unknown
};

// The lengths colonization runs at. ReconstructTree derives them from the cloud's measured
// scale (ReconstructionScale); the defaults suit a cloud sampled about every centimetre.
struct ColonizationLengths {
  double step_m = 0.02;              // metres, the growth step D
  double influence_radius_m = 0.08;  // metres, d_i: a node perceives points this close
  double kill_radius_m = 0.03;       // metres, d_k: a point this close to a node is reached
  double geodesic_slack_m = 0.05;    // metres of slack in the geodesic consistency test
  double bridge_gap_m = 0.25;        // metres, the longest gap bridged (0: none)

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

struct ColonizationOptions {
  // Thickness-scaled radii: a point is perceived within max(d_i, influence_per_thickness x its
  // thickness) and reached within max(d_k, kill_per_thickness x its thickness). 0 turns it off.
  double influence_per_thickness = 2.0;  // x the point's thickness
  double kill_per_thickness = 0.6;       // x the point's thickness
  // A node on thick wood also reaches every point within this x its own thickness (the radius of
  // the wood it stands on, from the points it reached first). 0 turns it off.
  double kill_per_node_thickness = 0.9;
  // Radians, half-angle of the perception cone around a node's growth direction (pi or more: no
  // cone).
  double perception_half_angle_rad = 1.4;
  // Share of a tip's previous direction kept in its next step (0: none). Off by default: with
  // recentring and skeleton smoothing after growth it changes nothing measurable
  // (docs/reconstruction.md).
  double direction_smoothing = 0.0;
  // Geodesic consistency: a node at geodesic g perceives a point at geodesic g' and distance d
  // only when -slack <= g' - g <= geodesic_ratio d + slack. Also off when the points carry no
  // geodesic.
  bool geodesic_consistency = true;
  double geodesic_ratio = 1.6;  // x the straight distance
  // Recentring: when growth ends, every node that reached points moves onto their weighted centre
  // (growth steps towards points but lands beside them by up to the kill radius).
  bool recenter = true;
  bool bridge_gaps = true;  // bridge gaps up to ColonizationLengths::bridge_gap_m once growth stops
  int max_nodes = 400000;   // growth stops at this many nodes

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

struct ColonizationStats {
  int iterations = 0;
  int bridges = 0;
  double reached_weight = 0.0;    // weight of points reached by some node
  double stuck_weight = 0.0;      // perceived but not reachable (growth would loop)
  double unreached_weight = 0.0;  // never perceived
};

// Grows from `root` (direction `root_direction`, e.g. the trunk axis). Every node's `support` is
// the weight of the points it reached and `thickness` their weighted mean thickness.
Skeleton GrowByColonization(std::span<const AttractionPoint> points, const Eigen::Vector3d& root,
                            const Eigen::Vector3d& root_direction,
                            const ColonizationLengths& lengths,
                            const ColonizationOptions& options = {},
                            ColonizationStats* stats = nullptr);

}  // namespace simtree::reconstruction
