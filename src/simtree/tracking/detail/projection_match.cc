#include "simtree/tracking/detail/projection_match.h"

#include <algorithm>
#include <cmath>

#include "simtree/core/units.h"
#include "simtree/tracking/detail/hungarian.h"

namespace simtree::tracking::detail {
namespace {

using Similarity = Eigen::Matrix3d;  // a 2D similarity in homogeneous coordinates

Eigen::Vector2d Apply(const Similarity& t, const Eigen::Vector2d& p) {
  return t.topLeftCorner<2, 2>() * p + t.topRightCorner<2, 1>();
}

Similarity Shift(const Eigen::Vector2d& d) {
  Similarity t = Similarity::Identity();
  t.topRightCorner<2, 1>() = d;
  return t;
}

// The pairs (projection, its nearest blob) that agree with `t`, and how well.
struct Agreement {
  std::vector<int> projection, blob;
  double residual = 0.0;  // summed distance (px)
  bool BetterThan(const Agreement& o) const {
    if (projection.size() != o.projection.size()) return projection.size() > o.projection.size();
    return residual < o.residual;
  }
};

Agreement Agree(const std::vector<Eigen::Vector2d>& projections,
                const std::vector<Eigen::Vector2d>& blobs, const Similarity& t, double radius) {
  Agreement a;
  for (size_t i = 0; i < projections.size(); ++i) {
    const Eigen::Vector2d q = Apply(t, projections[i]);
    int best = -1;
    double best_d = radius;
    for (size_t j = 0; j < blobs.size(); ++j) {
      const double d = (blobs[j] - q).norm();
      if (d <= best_d) best = static_cast<int>(j), best_d = d;
    }
    if (best < 0) continue;
    a.projection.push_back(static_cast<int>(i));
    a.blob.push_back(best);
    a.residual += best_d;
  }
  return a;
}

// The shift most projections agree on, among the offsets of projection-blob pairs within the
// projection's gate (ties: the smaller residual, then the smaller shift).
Eigen::Vector2d VoteShift(const std::vector<Eigen::Vector2d>& projections,
                          const std::vector<double>& gates,
                          const std::vector<Eigen::Vector2d>& blobs, double radius) {
  Eigen::Vector2d best_shift = Eigen::Vector2d::Zero();
  Agreement best;
  bool any = false;
  for (size_t i = 0; i < projections.size(); ++i) {
    for (const Eigen::Vector2d& b : blobs) {
      const Eigen::Vector2d d = b - projections[i];
      if (d.norm() > gates[i]) continue;
      const Agreement a = Agree(projections, blobs, Shift(d), radius);
      if (!any || a.BetterThan(best) || (!best.BetterThan(a) && d.norm() < best_shift.norm())) {
        best = a, best_shift = d, any = true;
      }
    }
  }
  return best_shift;
}

// A similarity fitted to the agreeing pairs, or `fallback` when there are too few or it is no
// pose error (turns or scales too much).
Similarity FitSimilarity(const std::vector<Eigen::Vector2d>& projections,
                         const std::vector<Eigen::Vector2d>& blobs, const Agreement& a,
                         const Similarity& fallback, const ProjectionMatchOptions& options) {
  const int n = static_cast<int>(a.projection.size());
  if (n < options.min_pairs_for_similarity || n < 2) return fallback;
  // Least squares in closed form (as complex numbers: q = a p + t, a = scale e^{i angle}).
  Eigen::Vector2d from_mean = Eigen::Vector2d::Zero(), to_mean = Eigen::Vector2d::Zero();
  for (int k = 0; k < n; ++k) {
    from_mean += projections[a.projection[k]] / n;
    to_mean += blobs[a.blob[k]] / n;
  }
  double dot = 0.0, cross = 0.0, norm = 0.0;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d p = projections[a.projection[k]] - from_mean;
    const Eigen::Vector2d q = blobs[a.blob[k]] - to_mean;
    dot += p.dot(q);
    cross += p.x() * q.y() - p.y() * q.x();
    norm += p.squaredNorm();
  }
  if (norm < 1e-9) return fallback;  // the pairs sit on one point: no rotation to fit
  Similarity t = Similarity::Identity();
  t.topLeftCorner<2, 2>() << dot / norm, -cross / norm, cross / norm, dot / norm;
  t.topRightCorner<2, 1>() = to_mean - t.topLeftCorner<2, 2>() * from_mean;
  const Eigen::Matrix2d sr = t.topLeftCorner<2, 2>();
  const double scale = std::hypot(sr(0, 0), sr(1, 0));
  const double angle = std::abs(std::atan2(sr(1, 0), sr(0, 0)));
  if (!t.allFinite() || std::abs(scale - 1.0) > options.max_scale_change ||
      angle > DegToRad(options.max_rotation_deg)) {
    return fallback;
  }
  return t;
}

// Hungarian assignment of blobs to points on pixel distance, pairs farther than `gate` refused.
std::vector<int> Assign(const std::vector<Eigen::Vector2d>& points,
                        const std::vector<Eigen::Vector2d>& blobs, double gate) {
  if (blobs.empty()) return std::vector<int>(points.size(), -1);
  const double forbidden = 1e12;  // far beyond any pixel distance
  std::vector<std::vector<double>> cost(points.size(),
                                        std::vector<double>(blobs.size(), forbidden));
  for (size_t i = 0; i < points.size(); ++i) {
    for (size_t j = 0; j < blobs.size(); ++j) {
      const double d = (blobs[j] - points[i]).norm();
      if (d <= gate) cost[i][j] = d;
    }
  }
  return SolveAssignment(cost, forbidden);
}

}  // namespace

ProjectionMatch MatchProjections(const std::vector<Eigen::Vector2d>& projections,
                                 const std::vector<double>& gates_px,
                                 const std::vector<Eigen::Vector2d>& blobs,
                                 const ProjectionMatchOptions& options) {
  const double radius = options.match_radius_px;
  const Eigen::Vector2d shift = VoteShift(projections, gates_px, blobs, radius);
  Similarity t = Shift(shift);
  Agreement agreement = Agree(projections, blobs, t, radius);
  // Twice: the similarity's pairs may add projections the shift alone left out (a roll error).
  for (int pass = 0; pass < 2; ++pass) {
    const Similarity fitted = FitSimilarity(projections, blobs, agreement, t, options);
    const Agreement refit = Agree(projections, blobs, fitted, radius);
    if (refit.projection.size() < agreement.projection.size()) break;
    t = fitted, agreement = refit;
  }

  ProjectionMatch out;
  out.agreeing = static_cast<int>(agreement.projection.size());
  const Eigen::Matrix2d sr = t.topLeftCorner<2, 2>();
  out.scale = std::hypot(sr(0, 0), sr(1, 0));
  out.rotation_deg = RadToDeg(std::atan2(sr(1, 0), sr(0, 0)));
  out.shift_px = t.topRightCorner<2, 1>();
  for (const Eigen::Vector2d& p : projections) out.corrected.push_back(Apply(t, p));
  const std::vector<int> first = Assign(out.corrected, blobs, radius);
  std::vector<double> residuals;
  for (size_t i = 0; i < first.size(); ++i) {
    if (first[i] >= 0) residuals.push_back((blobs[first[i]] - out.corrected[i]).norm());
  }
  out.gate_px = radius;
  if (!residuals.empty()) {
    std::nth_element(residuals.begin(), residuals.begin() + residuals.size() / 2, residuals.end());
    out.gate_px = std::clamp(options.residual_factor * residuals[residuals.size() / 2],
                             std::min(options.min_match_radius_px, radius), radius);
  }
  out.blob = Assign(out.corrected, blobs, out.gate_px);
  for (size_t i = 0; i < projections.size(); ++i) {
    out.distance_px.push_back(out.blob[i] < 0 ? -1.0
                                              : (blobs[out.blob[i]] - out.corrected[i]).norm());
  }
  return out;
}

}  // namespace simtree::tracking::detail
