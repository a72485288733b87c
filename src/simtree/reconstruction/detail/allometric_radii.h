#pragma once
// Branch radii by allometry, anchored on the measured trunk and corrected where the scan shows the
// wood well enough to measure it.
//
// The pipe model (Shinozaki et al. 1964; West, Brown and Enquist 1999): at a fork the parent's
// cross-section carries its children's, r_parent^n = sum r_child^n, with n about 2 (area
// preserving, da Vinci's rule) to 2.5-3 (elastic and hydraulic scaling). With every twig carrying
// the same pipe per unit of length it feeds, the radius at a node follows from the skeleton below
// it: r^n is proportional to W = (length of the subtree) + (tips below) x tip_length, which adds up
// exactly at forks and tapers along a branch. One measured radius sets the constant: the trunk's,
// from its MSAC cylinder, at the middle of the cylinder's stretch.
//
// Local fits: around each node the points near it (the node and its neighbours along the chain)
// are projected on the plane across the branch and a circle is fitted to them, centre free. A fit
// counts where the points are many, cover an arc of at least `fit_min_arc_rad` around the centre,
// lie on the circle (residual) and give a radius within a factor of the allometric one. A chain
// with counting fits is rescaled by the median ratio of fitted to allometric radius; a chain
// without inherits its parent chain's ratio, so a tree the model gets wrong is corrected
// throughout. With `recenter_on_fits`, a node with a counting fit moves onto the circle's centre:
// a branch scanned from one side leaves its samples near the visible surface, not on the axis.

#include <span>

#include <Eigen/Core>

#include "simtree/reconstruction/detail/skeleton.h"

namespace simtree::reconstruction {

struct RadiusOptions {
  double pipe_exponent = 2.5;      // n in r_parent^n = sum r_child^n
  double tip_length_m = 0.05;      // metres a tip is taken to feed beyond its last node
  double min_radius_m = 0.002;     // metres, the thinnest radius given
  bool local_fits = true;          // circle fits correct the radii (also off without points)
  bool recenter_on_fits = true;    // a node with a counting fit moves onto its centre
  int fit_min_points = 6;          // points a fit needs
  double fit_min_arc_rad = 2.6;    // radians of the circle holding points (~150 degrees)
  double fit_max_residual = 0.25;  // RMS distance from the circle, in radii...
  double fit_min_radius_over_noise = 2.0;  // ... and fitted radius >= this x the roughness
  double fit_max_ratio = 3.0;              // fitted within [1/x, x] of the allometric radius
  double max_correction = 3.0;             // a chain's ratio is clamped to [1/max, max]

  // Throws OptionError naming the first field out of range.
  void Validate() const;
};

struct RadiusStats {
  double anchor_radius_m = 0.0;
  int anchor_node = 0;
  int chains = 0;
  int chains_fitted = 0;  // chains whose radii come from local fits
  int nodes_fitted = 0;   // nodes with a counting circle fit
};

// Sets every node's radius (and, with recenter_on_fits, moves fitted nodes onto their axis).
// `anchor_node` and `anchor_radius_m` come from the trunk fit (anchor_radius_m <= 0: the root gets
// `fallback_root_radius_m`). `points` are the scan points used for local fits and `roughness_m`
// their surface roughness.
void AssignRadii(Skeleton& skeleton, int anchor_node, double anchor_radius_m,
                 double fallback_root_radius_m, std::span<const Eigen::Vector3d> points,
                 double roughness_m, const RadiusOptions& options, RadiusStats* stats = nullptr);

// W of every node: subtree length plus tips x tip_length (the allometric weight).
std::vector<double> AllometricWeights(const Skeleton& skeleton, double tip_length_m);

}  // namespace simtree::reconstruction
