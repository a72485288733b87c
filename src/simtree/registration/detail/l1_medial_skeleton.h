#pragma once
// The L1-medial skeleton of a point set (Huang et al. 2013, "L1-medial skeleton of point cloud"),
// the paper's Eq. 1:
//
//   argmin_X  sum_i sum_j ||x_i - q_j|| theta(||x_i - q_j||)  +  R(X),
//   theta(r) = exp(-r^2 / (h/2)^2),
//
// solved by the fixed-point iteration of Huang et al.: each skeleton point moves to the
// theta-weighted L1 median of the input points around it, and the repulsion term R(X) pushes
// skeleton points apart along the skeleton (weighted by how line-like their neighbourhood is,
// sigma_i) so they spread along a branch instead of collapsing into a few clumps:
//
//   x_i <- sum_j q_j a_ij / sum_j a_ij  +  mu sigma_i sum_i' (x_i - x_i') b_ii' / sum_i' b_ii',
//   a_ij = theta(||x_i - q_j||) / ||x_i - q_j||,   b_ii' = theta(||x_i - x_i'||) / ||x_i -
//   x_i'||^2.
//
// The neighbourhood h grows over a few rounds so the points contract to the medial axis of
// branches of different thickness. Points that converge onto each other are merged.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace simtree::registration {

struct SkeletonOptions {
  // Initial skeleton points: a seeded sample of the input, `sample_share` of it, at most
  // `max_points`.
  double sample_share = 0.08;
  int max_points = 1200;
  int min_points = 20;
  // Neighbourhood h: starts at `initial_radius_m` and grows by `radius_growth` times per round.
  double initial_radius_m = 0.06;
  double radius_growth = 1.35;
  int rounds = 3;
  int iterations_per_round = 6;
  double repulsion_mu = 0.35;  // Huang et al.: mu in [0, 1/2)
  // Skeleton points closer than this share of the final h are merged.
  double merge_share = 0.2;
  uint64_t seed = 1;
};

struct Skeleton {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> directionality;  // sigma_i in [1/3, 1]: 1 on a line
  double final_radius_m = 0.0;
  int iterations = 0;
};

// Empty skeleton for an empty input.
Skeleton L1MedialSkeleton(const std::vector<Eigen::Vector3d>& input,
                          const SkeletonOptions& options = {});

}  // namespace simtree::registration
