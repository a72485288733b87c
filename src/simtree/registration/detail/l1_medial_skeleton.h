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
  // Initial skeleton points: a seeded sample of the input, `sample_share` of it, within
  // [min_points, max_points].
  double sample_share = 0.08;  // [0, 1]
  int max_points = 1200;       // >= 1
  int min_points = 20;         // >= 1, <= max_points
  // Neighbourhood h: starts at `initial_radius_m` and grows by `radius_growth` times per round.
  double initial_radius_m = 0.06;  // m, > 0
  double radius_growth = 1.35;     // >= 1
  int rounds = 3;                  // >= 1
  int iterations_per_round = 6;    // >= 1
  double repulsion_mu = 0.35;      // [0, 0.5]: Huang et al.'s mu, in [0, 1/2)
  double merge_share = 0.2;        // >= 0: points closer than this share of the final h are merged
  uint64_t seed = 1;               // of the initial sample

  // Throws InputError naming the field of a nonsense value.
  void Validate() const;
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
