#include "simtree/registration/detail/sac_ia.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>

#include <open3d/geometry/KDTreeFlann.h>
#include <Eigen/Geometry>

#include "simtree/core/option_checks.h"

namespace simtree::registration {
namespace {

using open3d::geometry::KDTreeFlann;
using open3d::geometry::PointCloud;

struct Score {
  double truncated = std::numeric_limits<double>::infinity();  // mean truncated squared error
  int inliers = 0;
  double inlier_squared = 0.0;
};

Score Evaluate(const PointCloud& source, const KDTreeFlann& target_tree,
               const Eigen::Isometry3d& transform, double inlier_distance) {
  Score score;
  const double cap = inlier_distance * inlier_distance;
  double sum = 0.0;
  std::vector<int> index(1);
  std::vector<double> squared(1);
  for (const auto& p : source.points_) {
    if (target_tree.SearchKNN(Eigen::Vector3d(transform * p), 1, index, squared) < 1) {
      sum += cap;
      continue;
    }
    if (squared[0] < cap) {
      ++score.inliers;
      score.inlier_squared += squared[0];
      sum += squared[0];
    } else {
      sum += cap;
    }
  }
  score.truncated = sum / static_cast<double>(source.points_.size());
  return score;
}

}  // namespace

Eigen::Isometry3d FitRigid(const std::vector<Eigen::Vector3d>& from,
                           const std::vector<Eigen::Vector3d>& to,
                           const std::optional<Eigen::Vector3d>& from_up,
                           const std::optional<Eigen::Vector3d>& to_up) {
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  const size_t n = from.size();
  if (n == 0) return result;
  if (from_up && to_up) {
    const Eigen::Vector3d u = to_up->normalized();
    const Eigen::Matrix3d level =
        Eigen::Quaterniond::FromTwoVectors(from_up->normalized(), u).toRotationMatrix();
    Eigen::Vector3d from_mean = Eigen::Vector3d::Zero(), to_mean = Eigen::Vector3d::Zero();
    for (size_t k = 0; k < n; ++k) {
      from_mean += level * from[k];
      to_mean += to[k];
    }
    from_mean /= static_cast<double>(n);
    to_mean /= static_cast<double>(n);
    double sine = 0.0, cosine = 0.0;
    for (size_t k = 0; k < n; ++k) {
      Eigen::Vector3d a = level * from[k] - from_mean;
      Eigen::Vector3d b = to[k] - to_mean;
      a -= a.dot(u) * u;
      b -= b.dot(u) * u;
      sine += u.dot(a.cross(b));
      cosine += a.dot(b);
    }
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(std::atan2(sine, cosine), u).toRotationMatrix();
    result.linear() = turn * level;
    // from_mean is already levelled: the turn maps it onto the target's mean.
    result.translation() = to_mean - turn * from_mean;
    return result;
  }
  if (n < 3) {
    result.translation() = to[0] - from[0];
    return result;
  }
  Eigen::Matrix3Xd a(3, n), b(3, n);
  for (size_t k = 0; k < n; ++k) {
    a.col(k) = from[k];
    b.col(k) = to[k];
  }
  result.matrix() = Eigen::umeyama(a, b, false);
  return result;
}

void SacIaOptions::Validate() const {
  CheckAtLeast("iterations", iterations, 1);
  CheckAtLeast("samples", samples, 2);
  CheckAtLeast("feature_neighbors", feature_neighbors, 1);
  CheckNonNegative("min_sample_distance_m", min_sample_distance_m);
  CheckShare("edge_length_similarity", edge_length_similarity);
  CheckPositive("inlier_distance_m", inlier_distance_m);
  CheckNonNegative("refine_iterations", refine_iterations);
}

CoarseAlignment SampleConsensusInitialAlignment(
    const PointCloud& source, const open3d::pipelines::registration::Feature& source_features,
    const PointCloud& target, const open3d::pipelines::registration::Feature& target_features,
    const SacIaPrior& prior, const SacIaOptions& options) {
  options.Validate();
  const auto start = std::chrono::steady_clock::now();
  CoarseAlignment best;
  const int ns = static_cast<int>(source.points_.size());
  const int nt = static_cast<int>(target.points_.size());
  const int samples = std::max(2, options.samples);
  if (ns < samples || nt < samples) return best;
  const bool with_up = prior.source_up && prior.target_up;

  // The target points with the most similar features, for every source point.
  const KDTreeFlann feature_tree(target_features);
  const int k = std::min(options.feature_neighbors, nt);
  std::vector<std::vector<int>> similar(ns);
  {
    std::vector<double> squared;
    for (int i = 0; i < ns; ++i) {
      const Eigen::VectorXd f = source_features.data_.col(i);
      feature_tree.SearchKNN(f, k, similar[i], squared);
    }
  }
  const KDTreeFlann target_tree(target);
  std::mt19937_64 rng(options.seed);
  std::uniform_int_distribution<int> pick_source(0, ns - 1);
  std::uniform_int_distribution<int> pick_similar(0, k - 1);

  Score best_score;
  std::vector<Eigen::Vector3d> from(samples), to(samples);
  std::vector<int> chosen(samples);
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    // Draw well-spread source points.
    bool spread = true;
    for (int s = 0; s < samples && spread; ++s) {
      int tries = 0;
      for (;;) {
        chosen[s] = pick_source(rng);
        bool far = true;
        for (int r = 0; r < s; ++r) {
          if ((source.points_[chosen[s]] - source.points_[chosen[r]]).norm() <
              options.min_sample_distance_m) {
            far = false;
          }
        }
        if (far) break;
        if (++tries > 20) {
          spread = false;
          break;
        }
      }
    }
    if (!spread) continue;
    for (int s = 0; s < samples; ++s) {
      from[s] = source.points_[chosen[s]];
      const auto& candidates = similar[chosen[s]];
      if (candidates.empty()) continue;
      to[s] = target.points_[candidates[pick_similar(rng) % candidates.size()]];
    }
    // Edge lengths must agree (a rigid motion keeps them).
    bool similar_edges = true;
    for (int a = 0; a < samples && similar_edges; ++a) {
      for (int b = a + 1; b < samples; ++b) {
        const double ls = (from[a] - from[b]).norm(), lt = (to[a] - to[b]).norm();
        if (std::min(ls, lt) < options.edge_length_similarity * std::max(ls, lt)) {
          similar_edges = false;
          break;
        }
      }
    }
    if (!similar_edges) continue;
    const Eigen::Isometry3d transform =
        with_up ? FitRigid(from, to, prior.source_up, prior.target_up) : FitRigid(from, to);
    if (prior.max_center_offset_m > 0 && prior.source_center && prior.target_center &&
        (transform * *prior.source_center - *prior.target_center).norm() >
            prior.max_center_offset_m) {
      continue;
    }
    ++best.hypotheses;
    const Score score = Evaluate(source, target_tree, transform, options.inlier_distance_m);
    if (score.truncated < best_score.truncated) {
      best_score = score;
      best.target_from_source = transform;
      best.found = true;
    }
  }
  if (!best.found) {
    best.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return best;
  }

  // Refine on the matched points (closest points within the inlier distance).
  std::vector<int> index(1);
  std::vector<double> squared(1);
  for (int iteration = 0; iteration < options.refine_iterations; ++iteration) {
    std::vector<Eigen::Vector3d> a, b;
    for (const auto& p : source.points_) {
      if (target_tree.SearchKNN(Eigen::Vector3d(best.target_from_source * p), 1, index, squared) <
              1 ||
          squared[0] > options.inlier_distance_m * options.inlier_distance_m) {
        continue;
      }
      a.push_back(p);
      b.push_back(target.points_[index[0]]);
    }
    if (a.size() < 3) break;
    const Eigen::Isometry3d refined =
        with_up ? FitRigid(a, b, prior.source_up, prior.target_up) : FitRigid(a, b);
    const Score score = Evaluate(source, target_tree, refined, options.inlier_distance_m);
    if (score.truncated >= best_score.truncated) break;
    best_score = score;
    best.target_from_source = refined;
  }
  best.inlier_share = static_cast<double>(best_score.inliers) / ns;
  best.rmse_m =
      best_score.inliers > 0 ? std::sqrt(best_score.inlier_squared / best_score.inliers) : 0.0;
  best.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return best;
}

}  // namespace simtree::registration
