#include "simtree/registration/detail/gated_icp.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <numeric>
#include <random>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_reduce.h>
#include <Eigen/SVD>

#include "simtree/core/option_checks.h"

namespace simtree::registration {
namespace {

using open3d::geometry::KDTreeFlann;
using open3d::geometry::PointCloud;

// The sums below use TBB's deterministic reduce: the plain one splits work by stealing, so the
// order floating-point sums are added in, and a borderline pair's outcome, changed from run to
// run with the machine's load.

// Target points searched per source point for one whose normal agrees.
constexpr int kCandidates = 4;

// Normal equations of one Gauss-Newton step and the correspondence statistics.
struct Accumulator {
  Eigen::Matrix<double, 6, 6> jtj = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> jtr = Eigen::Matrix<double, 6, 1>::Zero();
  double squared = 0.0;
  int count = 0;
  void Join(const Accumulator& other) {
    jtj += other.jtj;
    jtr += other.jtr;
    squared += other.squared;
    count += other.count;
  }
};

std::vector<size_t> SampleIndices(size_t n, size_t wanted, uint64_t seed) {
  std::vector<size_t> indices(n);
  std::iota(indices.begin(), indices.end(), 0);
  if (wanted == 0 || n <= wanted) return indices;
  std::mt19937_64 rng(seed);
  std::shuffle(indices.begin(), indices.end(), rng);
  indices.resize(wanted);
  std::sort(indices.begin(), indices.end());
  return indices;
}

Eigen::Isometry3d Exp(const Eigen::Matrix<double, 6, 1>& step) {
  Eigen::Isometry3d update = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d w = step.head<3>();
  const double angle = w.norm();
  if (angle > 0) update.linear() = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
  update.translation() = step.tail<3>();
  return update;
}

// Residuals of the source segment's ends and middle against the target line (two components
// across it each), added to the normal equations so that the line weighs `line.weight` times the
// `count` surface correspondences.
void AddLine(const LineConstraint& line, const Eigen::Isometry3d& transform, int count,
             Eigen::Matrix<double, 6, 6>& jtj, Eigen::Matrix<double, 6, 1>& jtr) {
  if (count <= 0 || line.weight <= 0) return;
  const Eigen::Vector3d d = line.target_direction.normalized();
  const Eigen::Vector3d e1 = d.unitOrthogonal();
  const Eigen::Vector3d e2 = d.cross(e1);
  const double weight = line.weight * count / 6.0;
  for (double t : {-1.0, 0.0, 1.0}) {
    const Eigen::Vector3d x =
        transform * (line.source_point + t * line.source_half_length_m * line.source_direction);
    const Eigen::Vector3d offset = x - line.target_point;
    for (const Eigen::Vector3d& e : {e1, e2}) {
      Eigen::Matrix<double, 6, 1> j;
      j.head<3>() = x.cross(e);
      j.tail<3>() = e;
      jtj += weight * j * j.transpose();
      jtr += weight * j * offset.dot(e);
    }
  }
}

// Point-to-plane residuals of the source's plane points against the target's plane.
void AddPlane(const PlaneConstraint& plane, const Eigen::Isometry3d& transform, int count,
              Eigen::Matrix<double, 6, 6>& jtj, Eigen::Matrix<double, 6, 1>& jtr) {
  if (count <= 0 || plane.weight <= 0 || plane.source_points.empty()) return;
  const double weight = plane.weight * count / static_cast<double>(plane.source_points.size());
  const Eigen::Vector3d& n = plane.target_normal;
  for (const Eigen::Vector3d& p : plane.source_points) {
    const Eigen::Vector3d x = transform * p;
    Eigen::Matrix<double, 6, 1> j;
    j.head<3>() = x.cross(n);
    j.tail<3>() = n;
    jtj += weight * j * j.transpose();
    jtr += weight * j * (n.dot(x) + plane.target_offset);
  }
}

}  // namespace

void GatedIcpOptions::Validate() const {
  CheckPositiveList("max_distances_m", max_distances_m, false);
  CheckAtLeast("iterations_per_stage", iterations_per_stage, 1);
  CheckInRange("max_normal_angle_deg", max_normal_angle_deg, 0.0, 180.0);
  CheckNonNegative("huber_share", huber_share);
  CheckShare("min_planarity", min_planarity);
  CheckNonNegative("min_rotation_step", min_rotation_step);
  CheckNonNegative("min_translation_step", min_translation_step);
}

void MedialShiftOptions::Validate() const {
  CheckPositiveList("max_distances_m", max_distances_m, false);
  CheckAtLeast("iterations_per_stage", iterations_per_stage, 1);
  CheckNonNegative("min_step_m", min_step_m);
  CheckAtLeast("min_matches", min_matches, 3);
}

IcpResult GatedPointToPlaneIcp(const PointCloud& source, const PointCloud& target,
                               const KDTreeFlann& target_tree, const Eigen::Isometry3d& initial,
                               const GatedIcpOptions& options,
                               const std::vector<float>* source_planarity,
                               const std::vector<float>* target_planarity,
                               const IcpPriors& priors) {
  options.Validate();
  const auto start = std::chrono::steady_clock::now();
  IcpResult result;
  result.target_from_source = initial;
  if (source.points_.empty() || target.points_.empty() || !source.HasNormals() ||
      !target.HasNormals()) {
    return result;
  }
  std::vector<size_t> usable;
  for (size_t i = 0; i < source.points_.size(); ++i) {
    if (!source_planarity || (*source_planarity)[i] >= options.min_planarity) usable.push_back(i);
  }
  std::vector<size_t> sample =
      SampleIndices(usable.size(), options.max_source_points, options.seed);
  for (size_t& s : sample) s = usable[s];
  const double min_cos = std::cos(options.max_normal_angle_deg * std::numbers::pi / 180.0);

  Eigen::Isometry3d transform = initial;
  for (double distance : options.max_distances_m) {
    const double max_squared = distance * distance;
    for (int iteration = 0; iteration < options.iterations_per_stage; ++iteration) {
      ++result.iterations;
      const Eigen::Matrix3d rotation = transform.linear();
      const Accumulator sum = oneapi::tbb::parallel_deterministic_reduce(
          oneapi::tbb::blocked_range<size_t>(0, sample.size(), 256), Accumulator{},
          [&](const oneapi::tbb::blocked_range<size_t>& range, Accumulator acc) {
            std::vector<int> index(kCandidates);
            std::vector<double> squared(kCandidates);
            for (size_t s = range.begin(); s != range.end(); ++s) {
              const size_t i = sample[s];
              const Eigen::Vector3d p = transform * source.points_[i];
              const int found = target_tree.SearchKNN(p, kCandidates, index, squared);
              const Eigen::Vector3d normal = rotation * source.normals_[i];
              // The nearest target point within the distance whose normal agrees.
              int match = -1;
              for (int c = 0; c < found && squared[c] <= max_squared; ++c) {
                if (target_planarity && (*target_planarity)[index[c]] < options.min_planarity) {
                  continue;
                }
                if (normal.dot(target.normals_[index[c]]) >= min_cos) {
                  match = c;
                  break;
                }
              }
              if (match < 0) continue;
              const Eigen::Vector3d& q = target.points_[index[match]];
              // Half the normals' sum: at most unit length, so the Huber scale holds for both.
              const Eigen::Vector3d n =
                  options.objective == IcpObjective::kSymmetric
                      ? Eigen::Vector3d(0.5 * (normal + target.normals_[index[match]]))
                      : target.normals_[index[match]];
              const double r = (p - q).dot(n);
              // Huber weight at a share of the stage distance.
              const double k = distance * options.huber_share;
              const double weight = k <= 0 || std::abs(r) <= k ? 1.0 : k / std::abs(r);
              Eigen::Matrix<double, 6, 1> j;
              j.head<3>() = p.cross(n);
              j.tail<3>() = n;
              acc.jtj += weight * j * j.transpose();
              acc.jtr += weight * j * r;
              acc.squared += squared[match];
              ++acc.count;
            }
            return acc;
          },
          [](Accumulator a, const Accumulator& b) {
            a.Join(b);
            return a;
          });
      if (sum.count < 6) break;
      Eigen::Matrix<double, 6, 6> jtj = sum.jtj;
      Eigen::Matrix<double, 6, 1> jtr = sum.jtr;
      if (priors.line) AddLine(*priors.line, transform, sum.count, jtj, jtr);
      if (priors.plane) AddPlane(*priors.plane, transform, sum.count, jtj, jtr);
      // A whisker of damping keeps a direction nothing constrains (a straight trunk alone along
      // its axis) from wandering.
      jtj += 1e-6 * (jtj.trace() / 6.0 + 1e-12) * Eigen::Matrix<double, 6, 6>::Identity();
      const Eigen::Matrix<double, 6, 1> step = jtj.ldlt().solve(-jtr);
      if (!step.allFinite()) break;
      transform = Exp(step) * transform;
      if (step.head<3>().norm() < options.min_rotation_step &&
          step.tail<3>().norm() < options.min_translation_step) {
        break;
      }
    }
  }
  result.target_from_source = transform;
  const double last = options.max_distances_m.empty() ? 0.0 : options.max_distances_m.back();
  const Overlap overlap =
      MeasureOverlap(source, target, target_tree, transform, last, options.max_normal_angle_deg);
  result.fitness = overlap.share;
  result.rmse_m = overlap.rmse_m;
  result.correspondences = overlap.matched;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

// Stage by stage, each source medial point is matched to the nearest target medial point within
// the stage's distance (Huber-weighted: medial points scatter across their axes), then the
// weighted fit of the matches: a point-to-point rigid fit (Kabsch) with options.rotation, else
// the mean offset alone.
MedialShiftResult AlignMedialAxes(const PointCloud& source_medial, const PointCloud& target_medial,
                                  const KDTreeFlann& target_tree, const Eigen::Isometry3d& initial,
                                  const MedialShiftOptions& options) {
  options.Validate();
  MedialShiftResult result;
  result.target_from_source = initial;
  if (source_medial.points_.empty() || target_medial.points_.empty()) return result;
  struct Sum {
    Eigen::Vector3d source = Eigen::Vector3d::Zero(), target = Eigen::Vector3d::Zero();
    Eigen::Matrix3d cross = Eigen::Matrix3d::Zero();  // sum of w p q^T
    double weight = 0.0;
    int count = 0;
  };
  Eigen::Isometry3d transform = initial;
  int matches = 0;
  for (double distance : options.max_distances_m) {
    const double max_squared = distance * distance;
    const double k = distance / 3.0;
    for (int iteration = 0; iteration < options.iterations_per_stage; ++iteration) {
      const Sum sum = oneapi::tbb::parallel_deterministic_reduce(
          oneapi::tbb::blocked_range<size_t>(0, source_medial.points_.size(), 512), Sum{},
          [&](const oneapi::tbb::blocked_range<size_t>& range, Sum acc) {
            std::vector<int> index(1);
            std::vector<double> squared(1);
            for (size_t i = range.begin(); i != range.end(); ++i) {
              const Eigen::Vector3d p = transform * source_medial.points_[i];
              if (target_tree.SearchKNN(p, 1, index, squared) < 1 || squared[0] > max_squared) {
                continue;
              }
              const Eigen::Vector3d& q = target_medial.points_[index[0]];
              const double d = std::sqrt(squared[0]);
              const double w = d <= k ? 1.0 : k / d;
              acc.source += w * p;
              acc.target += w * q;
              acc.cross += w * p * q.transpose();
              acc.weight += w;
              ++acc.count;
            }
            return acc;
          },
          [](Sum a, const Sum& b) {
            a.source += b.source;
            a.target += b.target;
            a.cross += b.cross;
            a.weight += b.weight;
            a.count += b.count;
            return a;
          });
      matches = sum.count;
      if (sum.count < options.min_matches || sum.weight <= 0) break;
      const Eigen::Vector3d ps = sum.source / sum.weight, qs = sum.target / sum.weight;
      Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
      if (options.rotation) {
        const Eigen::Matrix3d h = sum.cross - sum.weight * ps * qs.transpose();
        const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
        Eigen::Matrix3d fix = Eigen::Matrix3d::Identity();
        fix(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
        step.linear() = svd.matrixV() * fix * svd.matrixU().transpose();
      }
      step.translation() = qs - step.linear() * ps;
      if (!step.matrix().allFinite()) break;
      transform = step * transform;
      if (step.translation().norm() < options.min_step_m &&
          Eigen::AngleAxisd(step.linear()).angle() < options.min_step_m) {
        break;
      }
    }
  }
  result.matches = matches;
  if (matches < options.min_matches || !transform.matrix().allFinite()) return result;
  // How far the source's medial points' centre moved.
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : source_medial.points_) centre += p;
  centre /= static_cast<double>(source_medial.points_.size());
  result.shift = transform * centre - initial * centre;
  result.target_from_source = transform;
  return result;
}

Overlap MeasureOverlap(const PointCloud& source, const PointCloud& target,
                       const KDTreeFlann& target_tree, const Eigen::Isometry3d& transform,
                       double distance_m, double max_normal_angle_deg) {
  Overlap overlap;
  if (source.points_.empty()) return overlap;
  const bool gate = max_normal_angle_deg < 180.0 && source.HasNormals() && target.HasNormals();
  const double min_cos = std::cos(max_normal_angle_deg * std::numbers::pi / 180.0);
  const double max_squared = distance_m * distance_m;
  struct Sum {
    double squared = 0.0;
    int count = 0;
  };
  const Sum sum = oneapi::tbb::parallel_deterministic_reduce(
      oneapi::tbb::blocked_range<size_t>(0, source.points_.size(), 512), Sum{},
      [&](const oneapi::tbb::blocked_range<size_t>& range, Sum acc) {
        const int k = gate ? kCandidates : 1;
        std::vector<int> index(k);
        std::vector<double> squared(k);
        for (size_t i = range.begin(); i != range.end(); ++i) {
          const Eigen::Vector3d p = transform * source.points_[i];
          const int found = target_tree.SearchKNN(p, k, index, squared);
          int match = -1;
          for (int c = 0; c < found && squared[c] <= max_squared; ++c) {
            if (!gate || (transform.linear() * source.normals_[i]).dot(target.normals_[index[c]]) >=
                             min_cos) {
              match = c;
              break;
            }
          }
          if (match < 0) continue;
          acc.squared += squared[match];
          ++acc.count;
        }
        return acc;
      },
      [](Sum a, const Sum& b) {
        a.squared += b.squared;
        a.count += b.count;
        return a;
      });
  overlap.matched = sum.count;
  overlap.share = static_cast<double>(sum.count) / static_cast<double>(source.points_.size());
  overlap.rmse_m = sum.count > 0 ? std::sqrt(sum.squared / sum.count) : 0.0;
  return overlap;
}

}  // namespace simtree::registration
