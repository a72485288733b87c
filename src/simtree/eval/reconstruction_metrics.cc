#include "simtree/eval/reconstruction_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "simtree/core/option_checks.h"
#include "simtree/reconstruction/detail/point_index.h"

namespace simtree::eval {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A tree's axes sampled every few millimetres, each sample knowing its segment so distances are
// measured to the segment itself, not to the sample.
class SkeletonSamples {
 public:
  struct Sample {
    Eigen::Vector3d position;
    double radius;
    double length;  // of axis this sample stands for
    int branch;
    int segment;  // nodes segment, segment + 1 of the branch
  };
  struct Nearest {
    double distance = kInf;  // to the axis
    double radius = 0.0;     // radius there
    int branch = -1;
  };

  SkeletonSamples(const Tree& tree, double step) : tree_(tree) {
    for (const Branch& b : tree.branches) {
      for (size_t k = 0; k + 1 < b.nodes.size(); ++k) {
        const Node& a = b.nodes[k];
        const Node& c = b.nodes[k + 1];
        const double length = (c.position - a.position).norm();
        const int count = std::max(1, static_cast<int>(std::ceil(length / step)));
        for (int i = 0; i < count; ++i) {
          const double t = (i + 0.5) / count;
          samples_.push_back({a.position + t * (c.position - a.position),
                              a.radius + t * (c.radius - a.radius), length / count, b.id,
                              static_cast<int>(k)});
        }
      }
    }
    std::vector<Eigen::Vector3d> positions(samples_.size());
    for (size_t i = 0; i < samples_.size(); ++i) positions[i] = samples_[i].position;
    index_ = std::make_unique<reconstruction::PointIndex>(positions);
  }

  const std::vector<Sample>& samples() const { return samples_; }
  bool empty() const { return samples_.empty(); }

  // Point-to-segment distance along with the parameter on the segment.
  double SegmentDistance(const Eigen::Vector3d& p, int branch, int segment, double* t,
                         double* radius) const {
    const Branch& b = tree_.branches[branch];
    const Node& a = b.nodes[segment];
    const Node& c = b.nodes[segment + 1];
    const Eigen::Vector3d d = c.position - a.position;
    const double l2 = d.squaredNorm();
    *t = l2 > 0 ? std::clamp((p - a.position).dot(d) / l2, 0.0, 1.0) : 0.0;
    *radius = a.radius + *t * (c.radius - a.radius);
    return (p - (a.position + *t * d)).norm();
  }

  Nearest NearestAxis(const Eigen::Vector3d& p, int k = 6) const {
    Nearest best;
    index_->Nearest(p, k, near_, d2_);
    for (const int i : near_) {
      const Sample& s = samples_[i];
      double t, r;
      const double d = SegmentDistance(p, s.branch, s.segment, &t, &r);
      if (d < best.distance) best = {d, r, s.branch};
    }
    return best;
  }

  // Distance from the surface of the union of frustums.
  double SurfaceDistance(const Eigen::Vector3d& p, double reach) const {
    index_->WithinRadius(p, reach, near_, d2_);
    if (near_.empty()) index_->Nearest(p, 8, near_, d2_);
    double outside = kInf, inside = kInf;
    segments_.clear();
    for (const int i : near_) {
      const Sample& s = samples_[i];
      const std::pair<int, int> key(s.branch, s.segment);
      if (std::find(segments_.begin(), segments_.end(), key) != segments_.end()) continue;
      segments_.push_back(key);
      double t, r;
      const double d = SegmentDistance(p, s.branch, s.segment, &t, &r);
      if (d < r) {
        inside = std::min(inside, r - d);
      } else {
        outside = std::min(outside, d - r);
      }
    }
    return std::isfinite(inside) ? inside : outside;
  }

 private:
  const Tree& tree_;
  std::vector<Sample> samples_;
  std::unique_ptr<reconstruction::PointIndex> index_;
  mutable std::vector<int> near_;
  mutable std::vector<double> d2_;
  mutable std::vector<std::pair<int, int>> segments_;
};

double Ratio(int a, int b) { return b > 0 ? static_cast<double>(a) / b : 0.0; }

// The branch of the other tree most of a branch's length lies along (-1 when none).
int MostAlong(const std::map<int, double>& along) {
  if (along.empty()) return -1;
  return std::max_element(along.begin(), along.end(),
                          [](const auto& a, const auto& b) { return a.second < b.second; })
      ->first;
}

// A true branch is scored when its base is at least min_true_radius_m thick.
bool ScoredTruth(const Tree& truth, int branch, const TruthScoreOptions& options) {
  return truth.branches[branch].nodes.front().radius >= options.min_true_radius_m;
}

// The branches of a tree, not matched yet.
std::vector<BranchMatch> ListBranches(const Tree& tree) {
  std::vector<BranchMatch> out;
  for (const Branch& b : tree.branches) {
    BranchMatch m;
    m.branch = b.id;
    m.level = b.level;
    m.length_m = b.Length();
    m.base_radius_m = b.nodes.front().radius;
    out.push_back(m);
  }
  return out;
}

// Per branch of one tree: how much of its length lies near the other tree's skeleton, and along
// which of the other's branches.
struct Coverage {
  std::vector<double> near, total;
  std::vector<std::map<int, double>> along;

  explicit Coverage(int branches) : near(branches, 0.0), total(branches, 0.0), along(branches) {}
  // Sets the match's near share, whether it counts as found and the branch it lies along.
  void Match(BranchMatch& m, double found_share) const {
    m.near_share = total[m.branch] > 0 ? near[m.branch] / total[m.branch] : 0.0;
    m.found = m.near_share > found_share;
    m.matched = MostAlong(along[m.branch]);
  }
};

// The true skeleton against the reconstruction: recall, completeness distance, radius error.
struct TruthSide {
  Coverage coverage;
  double distance_m = 0.0;        // mean over scored branches
  double thick_distance_m = 0.0;  // the same over wood >= min_true_radius_m
  double radius_error = 0.0;      // mean relative, where near
  double thick_length_m = 0.0;    // true wood >= min_true_radius_m
};

TruthSide CompareTruthToReconstruction(const SkeletonSamples& tru, const SkeletonSamples& rec,
                                       const Tree& truth, const TruthScoreOptions& options) {
  TruthSide out{Coverage(truth.size())};
  double sum_distance = 0.0, sum_weight = 0.0, radius_error = 0.0, radius_weight = 0.0;
  double thick_distance = 0.0, thick_weight = 0.0;
  for (const auto& s : tru.samples()) {
    const auto nearest = rec.NearestAxis(s.position);
    out.coverage.total[s.branch] += s.length;
    const bool near = nearest.distance <= options.near_distance_m + s.radius;
    if (near) {
      out.coverage.near[s.branch] += s.length;
      out.coverage.along[s.branch][nearest.branch] += s.length;
    }
    if (s.radius >= options.min_true_radius_m) out.thick_length_m += s.length;
    if (!ScoredTruth(truth, s.branch, options)) continue;
    sum_distance += s.length * nearest.distance;
    sum_weight += s.length;
    if (s.radius >= options.min_true_radius_m) {
      thick_distance += s.length * nearest.distance;
      thick_weight += s.length;
    }
    if (near && s.radius > 0) {
      radius_error += s.length * std::abs(nearest.radius - s.radius) / s.radius;
      radius_weight += s.length;
    }
  }
  out.distance_m = sum_weight > 0 ? sum_distance / sum_weight : 0.0;
  out.thick_distance_m = thick_weight > 0 ? thick_distance / thick_weight : 0.0;
  out.radius_error = radius_weight > 0 ? radius_error / radius_weight : 0.0;
  return out;
}

// The reconstruction against the true skeleton: precision, accuracy distance, and per branch the
// wood it claims: where the truth is thick enough to score, or where there is none.
struct ReconstructionSide {
  Coverage coverage;
  std::vector<double> claimed;  // metres per reconstructed branch
  double distance_m = 0.0;
};

ReconstructionSide CompareReconstructionToTruth(const SkeletonSamples& rec,
                                                const SkeletonSamples& tru,
                                                const Tree& reconstruction,
                                                const TruthScoreOptions& options) {
  ReconstructionSide out{Coverage(reconstruction.size()),
                         std::vector<double>(reconstruction.size(), 0.0)};
  double sum_distance = 0.0, sum_weight = 0.0;
  for (const auto& s : rec.samples()) {
    const auto nearest = tru.NearestAxis(s.position);
    out.coverage.total[s.branch] += s.length;
    sum_distance += s.length * nearest.distance;
    sum_weight += s.length;
    out.coverage.along[s.branch][nearest.branch] += s.length;
    const bool near = nearest.distance <= options.near_distance_m + nearest.radius;
    if (near) out.coverage.near[s.branch] += s.length;
    if (!near || nearest.radius >= options.min_true_radius_m) out.claimed[s.branch] += s.length;
  }
  out.distance_m = sum_weight > 0 ? sum_distance / sum_weight : 0.0;
  return out;
}

struct TrunkRadii {
  double reconstructed_m = 0.0, true_m = 0.0;  // means
  double error = 0.0;                          // |reconstructed / true - 1|
};

// Mean radii over the lowest trunk_height_m of the true trunk, every 2 cm: the true one there and
// the reconstruction's nearest.
TrunkRadii CompareTrunkRadii(const SkeletonSamples& rec, const Tree& truth,
                             const TruthScoreOptions& options) {
  const Branch& true_trunk = truth.trunk();
  const std::vector<double> arc = true_trunk.ArcLengths();
  double true_sum = 0.0, rec_sum = 0.0;
  int count = 0;
  for (double s = 0.0; s <= std::min(options.trunk_height_m, true_trunk.Length()); s += 0.02) {
    const Eigen::Vector3d p = true_trunk.PointAt(s);
    const size_t k =
        std::min<size_t>(std::upper_bound(arc.begin(), arc.end(), s) - arc.begin(), arc.size() - 1);
    const double t = k > 0 && arc[k] > arc[k - 1] ? (s - arc[k - 1]) / (arc[k] - arc[k - 1]) : 0;
    const double r_true =
        k > 0 ? true_trunk.nodes[k - 1].radius +
                    t * (true_trunk.nodes[k].radius - true_trunk.nodes[k - 1].radius)
              : true_trunk.nodes[0].radius;
    const auto nearest = rec.NearestAxis(p);
    true_sum += r_true;
    rec_sum += nearest.radius;
    ++count;
  }
  TrunkRadii out;
  if (count > 0 && true_sum > 0) {
    out.true_m = true_sum / count;
    out.reconstructed_m = rec_sum / count;
    out.error = std::abs(rec_sum / true_sum - 1.0);
  }
  return out;
}

}  // namespace

void TruthScoreOptions::Validate() const {
  CheckNonNegative("min_true_radius_m", min_true_radius_m);
  CheckNonNegative("near_distance_m", near_distance_m);
  CheckShare("found_share", found_share);
  CheckPositive("sample_step_m", sample_step_m);
  CheckNonNegative("trunk_height_m", trunk_height_m);
}

TruthScores ScoreAgainstTruth(const Tree& reconstruction, const Tree& truth,
                              const TruthScoreOptions& options) {
  options.Validate();
  TruthScores scores;
  const SkeletonSamples rec(reconstruction, options.sample_step_m);
  const SkeletonSamples tru(truth, options.sample_step_m);
  if (rec.empty() || tru.empty()) return scores;
  scores.truth = ListBranches(truth);
  for (BranchMatch& m : scores.truth) {
    m.scored = ScoredTruth(truth, m.branch, options);
    scores.true_total_length_m += m.length_m;
  }
  scores.reconstruction = ListBranches(reconstruction);
  for (const BranchMatch& m : scores.reconstruction) scores.total_length_m += m.length_m;

  const TruthSide truth_side = CompareTruthToReconstruction(tru, rec, truth, options);
  scores.truth_to_reconstruction_m = truth_side.distance_m;
  scores.thick_truth_to_reconstruction_m = truth_side.thick_distance_m;
  scores.radius_error = truth_side.radius_error;
  scores.true_length_m = truth_side.thick_length_m;
  for (BranchMatch& m : scores.truth) {
    truth_side.coverage.Match(m, options.found_share);
    if (!m.scored) continue;
    ++scores.true_branches;
    scores.found += m.found;
  }
  scores.recall = Ratio(scores.found, scores.true_branches);

  const ReconstructionSide rec_side =
      CompareReconstructionToTruth(rec, tru, reconstruction, options);
  scores.reconstruction_to_truth_m = rec_side.distance_m;
  for (BranchMatch& m : scores.reconstruction) {
    rec_side.coverage.Match(m, options.found_share);
    // Not scored: correct, but along true wood thinner than the scored radius.
    m.scored = !(m.found && m.matched >= 0 && !ScoredTruth(truth, m.matched, options));
    if (!m.scored) continue;
    // A branch along thin true wood claims none: where it leaves thick wood its start lies near
    // that wood.
    scores.length_m += rec_side.claimed[m.branch];
    ++scores.reconstructed_branches;
    scores.correct += m.found;
  }
  scores.precision = Ratio(scores.correct, scores.reconstructed_branches);
  scores.mean_skeleton_distance_m =
      0.5 * (scores.reconstruction_to_truth_m + scores.truth_to_reconstruction_m);
  scores.thick_skeleton_distance_m =
      0.5 * (scores.reconstruction_to_truth_m + scores.thick_truth_to_reconstruction_m);
  scores.length_error = scores.true_length_m > 0
                            ? (scores.length_m - scores.true_length_m) / scores.true_length_m
                            : 0.0;

  const TrunkRadii trunk = CompareTrunkRadii(rec, truth, options);
  scores.trunk_radius_m = trunk.reconstructed_m;
  scores.true_trunk_radius_m = trunk.true_m;
  scores.trunk_radius_error = trunk.error;
  return scores;
}

std::vector<double> SurfaceDistances(const Tree& tree, std::span<const Eigen::Vector3d> points) {
  std::vector<double> distances(points.size(), kInf);
  if (tree.empty()) return distances;
  double max_radius = 0.0;
  for (const Branch& b : tree.branches) {
    for (const Node& n : b.nodes) max_radius = std::max(max_radius, n.radius);
  }
  const SkeletonSamples samples(tree, 0.01);
  const double reach = std::min(max_radius, 0.5) + 0.05;
  for (size_t i = 0; i < points.size(); ++i) {
    distances[i] = samples.SurfaceDistance(points[i], reach);
  }
  return distances;
}

std::vector<int> BranchCountsByLevel(const Tree& tree) {
  std::vector<int> counts;
  for (const Branch& b : tree.branches) {
    if (b.level >= static_cast<int>(counts.size())) counts.resize(b.level + 1, 0);
    ++counts[b.level];
  }
  return counts;
}

CloudFitScores ScoreAgainstCloud(const Tree& reconstruction,
                                 std::span<const Eigen::Vector3d> points, double within_m) {
  CloudFitScores scores;
  scores.within_m = within_m;
  scores.branches = reconstruction.size();
  scores.branches_by_level = BranchCountsByLevel(reconstruction);
  for (const Branch& b : reconstruction.branches) scores.total_length_m += b.Length();
  std::vector<double> d = SurfaceDistances(reconstruction, points);
  scores.points = d.size();
  if (d.empty()) return scores;
  double sum = 0.0;
  size_t within = 0;
  for (const double v : d) {
    sum += v;
    within += v <= within_m;
  }
  scores.mean_distance_m = sum / d.size();
  scores.share_within = static_cast<double>(within) / d.size();
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  scores.median_distance_m = d[d.size() / 2];
  return scores;
}

std::string FormatTruthScores(const TruthScores& s) {
  return fmt::format(
      "recall {:.3f} ({}/{})  precision {:.3f} ({}/{})  skeleton distance {:.4f} m "
      "(rec->true {:.4f}, true->rec {:.4f})  radius error {:.3f}  trunk radius {:.4f} m vs "
      "{:.4f} m (error {:.3f})  length {:.2f} m vs {:.2f} m (error {:+.3f})",
      s.recall, s.found, s.true_branches, s.precision, s.correct, s.reconstructed_branches,
      s.mean_skeleton_distance_m, s.reconstruction_to_truth_m, s.truth_to_reconstruction_m,
      s.radius_error, s.trunk_radius_m, s.true_trunk_radius_m, s.trunk_radius_error, s.length_m,
      s.true_length_m, s.length_error);
}

std::string FormatCloudFit(const CloudFitScores& s) {
  std::string levels;
  for (size_t l = 0; l < s.branches_by_level.size(); ++l) {
    levels += fmt::format("{}{}: {}", l ? ", " : "", l, s.branches_by_level[l]);
  }
  return fmt::format(
      "{} points: mean distance to the surface {:.4f} m, median {:.4f} m, {:.1f}% within "
      "{:g} cm; {} branches (by level {}), {:.2f} m of wood",
      s.points, s.mean_distance_m, s.median_distance_m, 100.0 * s.share_within, 100.0 * s.within_m,
      s.branches, levels, s.total_length_m);
}

}  // namespace simtree::eval
