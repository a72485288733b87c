#include "simtree/registration/detail/l1_medial_skeleton.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include <oneapi/tbb/parallel_for.h>
#include <open3d/geometry/KDTreeFlann.h>
#include <open3d/geometry/PointCloud.h>
#include <Eigen/Eigenvalues>

#include "simtree/core/option_checks.h"

namespace simtree::registration {
namespace {

// sigma_i of Huang et al.: the largest eigenvalue's share of the theta-weighted covariance of the
// skeleton points around x_i (1/3 when isotropic, 1 on a line). `near` are x_i's neighbours
// within h (x_i itself included or not).
double Directionality(const std::vector<Eigen::Vector3d>& x, size_t i, const std::vector<int>& near,
                      double h) {
  const double inv = 1.0 / (0.25 * h * h);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (int k : near) {
    if (static_cast<size_t>(k) == i) continue;
    const Eigen::Vector3d d = x[k] - x[i];
    covariance += std::exp(-d.squaredNorm() * inv) * d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d lambda = solver.eigenvalues().cwiseMax(0.0);
  const double sum = lambda.sum();
  return sum > 0 ? lambda(2) / sum : 1.0 / 3.0;
}

}  // namespace

void SkeletonOptions::Validate() const {
  CheckShare("sample_share", sample_share);
  CheckAtLeast("max_points", max_points, 1);
  CheckAtLeast("min_points", min_points, 1);
  CheckOrdered("min_points", min_points, "max_points", max_points);
  CheckPositive("initial_radius_m", initial_radius_m);
  CheckAtLeast("radius_growth", radius_growth, 1.0);
  CheckAtLeast("rounds", rounds, 1);
  CheckAtLeast("iterations_per_round", iterations_per_round, 1);
  CheckInRange("repulsion_mu", repulsion_mu, 0.0, 0.5);
  CheckNonNegative("merge_share", merge_share);
}

Skeleton L1MedialSkeleton(const std::vector<Eigen::Vector3d>& input,
                          const SkeletonOptions& options) {
  options.Validate();
  Skeleton skeleton;
  if (input.empty()) return skeleton;
  open3d::geometry::PointCloud q_cloud;
  q_cloud.points_ = input;
  const open3d::geometry::KDTreeFlann q_tree(q_cloud);

  // Initial points: a seeded sample of the input.
  const int wanted =
      std::clamp(static_cast<int>(options.sample_share * input.size()),
                 std::min<int>(options.min_points, input.size()), std::max(1, options.max_points));
  std::vector<size_t> order(input.size());
  std::iota(order.begin(), order.end(), 0);
  std::mt19937_64 rng(options.seed);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<Eigen::Vector3d> x;
  for (int i = 0; i < wanted && i < static_cast<int>(order.size()); ++i)
    x.push_back(input[order[i]]);

  std::vector<Eigen::Vector3d> next(x.size());
  std::vector<double> sigma(x.size(), 1.0 / 3.0);
  double h = options.initial_radius_m;
  for (int round = 0; round < options.rounds; ++round, h *= options.radius_growth) {
    const double inv = 1.0 / (0.25 * h * h);
    for (int iteration = 0; iteration < options.iterations_per_round; ++iteration) {
      ++skeleton.iterations;
      // The skeleton points' own neighbourhoods, from a tree rebuilt as they move.
      open3d::geometry::PointCloud x_cloud;
      x_cloud.points_ = x;
      const open3d::geometry::KDTreeFlann x_tree(x_cloud);
      oneapi::tbb::parallel_for(size_t{0}, x.size(), [&](size_t i) {
        std::vector<int> near;
        std::vector<double> near_squared;
        x_tree.SearchRadius(x[i], h, near, near_squared);
        sigma[i] = Directionality(x, i, near, h);
        // Attraction: the theta-weighted L1 median of the input around x_i.
        std::vector<int> neighbours;
        std::vector<double> squared;
        q_tree.SearchRadius(x[i], h, neighbours, squared);
        Eigen::Vector3d attract = Eigen::Vector3d::Zero();
        double attract_weight = 0.0;
        for (size_t k = 0; k < neighbours.size(); ++k) {
          // The floor matters: x_i starts on an input point, whose 1/r weight would otherwise
          // hold it there (a fixed point of the Weiszfeld step).
          const double r = std::max(std::sqrt(squared[k]), 0.05 * h);
          const double a = std::exp(-squared[k] * inv) / r;
          attract += a * input[neighbours[k]];
          attract_weight += a;
        }
        if (attract_weight <= 0.0) {
          next[i] = x[i];  // nothing around: the point stays where it is
          return;
        }
        // Repulsion from the other skeleton points, along the skeleton.
        Eigen::Vector3d repel = Eigen::Vector3d::Zero();
        double repel_weight = 0.0;
        for (int k : near) {
          if (static_cast<size_t>(k) == i) continue;
          const Eigen::Vector3d d = x[i] - x[k];
          const double r2 = std::max(d.squaredNorm(), 1e-8 * h * h);
          const double b = std::exp(-r2 * inv) / r2;
          repel += b * d;
          repel_weight += b;
        }
        next[i] = attract / attract_weight;
        if (repel_weight > 0.0) next[i] += options.repulsion_mu * sigma[i] * repel / repel_weight;
      });
      x.swap(next);
    }
  }
  skeleton.final_radius_m = h / options.radius_growth;

  // Merge points that converged onto each other.
  const double merge = options.merge_share * skeleton.final_radius_m;
  std::vector<char> taken(x.size(), 0);
  for (size_t i = 0; i < x.size(); ++i) {
    if (taken[i]) continue;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double sigma_sum = 0.0;
    int count = 0;
    for (size_t k = i; k < x.size(); ++k) {
      if (taken[k] || (x[k] - x[i]).norm() > merge) continue;
      taken[k] = 1;
      sum += x[k];
      sigma_sum += sigma[k];
      ++count;
    }
    skeleton.points.push_back(sum / count);
    skeleton.directionality.push_back(sigma_sum / count);
  }
  return skeleton;
}

}  // namespace simtree::registration
