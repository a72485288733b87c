#include "reconstruction_misses.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <vector>

#include <Eigen/Eigenvalues>

#include "simtree/eval/reconstruction_metrics.h"
#include "simtree/reconstruction/detail/point_index.h"

namespace simtree::bench {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A tree's axes sampled every 5 mm, each sample with its radius and branch direction.
class Axes {
 public:
  explicit Axes(const Tree& tree) {
    for (const Branch& b : tree.branches) {
      for (size_t k = 0; k + 1 < b.nodes.size(); ++k) {
        const Node& a = b.nodes[k];
        const Node& c = b.nodes[k + 1];
        const Eigen::Vector3d d = c.position - a.position;
        const double length = d.norm();
        if (length <= 0) continue;
        const int count = std::max(1, static_cast<int>(std::ceil(length / 0.005)));
        for (int i = 0; i < count; ++i) {
          const double t = (i + 0.5) / count;
          position_.push_back(a.position + t * d);
          radius_.push_back(a.radius + t * (c.radius - a.radius));
          direction_.push_back(d / length);
        }
      }
    }
    index_ = std::make_unique<reconstruction::PointIndex>(position_);
  }

  // The sample whose surface is nearest `p` (among the 16 nearest axis samples).
  int NearestSurface(const Eigen::Vector3d& p) const {
    index_->Nearest(p, 16, near_, d2_);
    int best = -1;
    double best_d = kInf;
    for (size_t j = 0; j < near_.size(); ++j) {
      const double d = std::abs(std::sqrt(d2_[j]) - radius_[near_[j]]);
      if (d < best_d) best_d = d, best = near_[j];
    }
    return best;
  }
  // Distance from `p` to the nearest axis sample, and that sample.
  double AxisDistance(const Eigen::Vector3d& p, int* sample) const {
    index_->Nearest(p, 1, near_, d2_);
    *sample = near_[0];
    return std::sqrt(d2_[0]);
  }

  const Eigen::Vector3d& position(int i) const { return position_[i]; }
  double radius(int i) const { return radius_[i]; }
  const Eigen::Vector3d& direction(int i) const { return direction_[i]; }

 private:
  std::vector<Eigen::Vector3d> position_, direction_;
  std::vector<double> radius_;
  std::unique_ptr<reconstruction::PointIndex> index_;
  mutable std::vector<int> near_;
  mutable std::vector<double> d2_;
};

// What one missed point says.
struct Miss {
  int point = 0;
  int bucket = 0;        // radius class of our nearest branch
  bool outside = false;  // beyond our surface (not inside a too-thick tube)
  bool reference_fits = false;
  bool reference_apart = false;    // the reference's axis there lies outside our wood by > 2 cm
  bool reference_thicker = false;  // same wood, the reference's radius > 1.3x ours
  double radius_ratio = 0.0;       // reference / ours at that place
  int our_sample = -1;
  Eigen::Vector3d reference_axis = Eigen::Vector3d::Zero();
  double axis_distance = 0.0;
};

constexpr std::array<double, 5> kBucketTops = {0.003, 0.010, 0.030, 0.100, kInf};
const char* const kBucketNames[] = {"< 3 mm", "3-10 mm", "10-30 mm", "30-100 mm", ">= 100 mm"};

int Bucket(double r) {
  int b = 0;
  while (r >= kBucketTops[b]) ++b;
  return b;
}

std::vector<Miss> ClassifyMisses(const Axes& ours, const Axes& reference,
                                 const std::vector<double>& our_d, const std::vector<double>& ref_d,
                                 std::span<const Eigen::Vector3d> points) {
  std::vector<Miss> misses;
  for (size_t i = 0; i < points.size(); ++i) {
    if (our_d[i] <= 0.02 || our_d[i] > 0.10) continue;
    Miss m;
    m.point = static_cast<int>(i);
    m.our_sample = ours.NearestSurface(points[i]);
    const double r = ours.radius(m.our_sample);
    m.axis_distance = (points[i] - ours.position(m.our_sample)).norm();
    m.bucket = Bucket(r);
    m.outside = m.axis_distance > r;
    m.reference_fits = ref_d[i] <= 0.02;
    if (m.reference_fits) {
      const int s = reference.NearestSurface(points[i]);
      int near = 0;
      const double g = ours.AxisDistance(reference.position(s), &near);
      m.reference_apart = g > ours.radius(near) + 0.02;
      m.reference_axis = reference.position(s);
      m.radius_ratio = reference.radius(s) / std::max(ours.radius(near), 1e-4);
      m.reference_thicker = !m.reference_apart && m.radius_ratio > 1.3;
    }
    misses.push_back(m);
  }
  return misses;
}

// Clusters of missed points (links up to `link_m`); a cluster is a twig when it is elongated
// (first principal spread >= 3x the second, >= 3 links long) and leaves the branch: its direction
// 30 degrees or more off the branch's, or its distance from our axis spans 3 cm or more.
std::vector<char> TwigPoints(const std::vector<Miss>& misses, const Axes& ours,
                             std::span<const Eigen::Vector3d> points, double link_m) {
  std::vector<Eigen::Vector3d> p(misses.size());
  for (size_t i = 0; i < misses.size(); ++i) p[i] = points[misses[i].point];
  std::vector<int> root(p.size());
  std::iota(root.begin(), root.end(), 0);
  auto find = [&](int i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  const reconstruction::PointIndex index(p);
  std::vector<int> near;
  std::vector<double> d2;
  for (size_t i = 0; i < p.size(); ++i) {
    index.WithinRadius(p[i], link_m, near, d2);
    for (const int j : near) root[find(static_cast<int>(i))] = find(j);
  }
  std::vector<std::vector<int>> clusters(p.size());
  for (size_t i = 0; i < p.size(); ++i) clusters[find(static_cast<int>(i))].push_back(i);
  std::vector<char> twig(p.size(), 0);
  for (const std::vector<int>& c : clusters) {
    if (c.size() < 4) continue;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const int i : c) mean += p[i];
    mean /= c.size();
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    double lo = kInf, hi = 0;
    Eigen::Vector3d branch = Eigen::Vector3d::Zero();
    for (const int i : c) {
      cov += (p[i] - mean) * (p[i] - mean).transpose();
      lo = std::min(lo, misses[i].axis_distance);
      hi = std::max(hi, misses[i].axis_distance);
      const Eigen::Vector3d& d = ours.direction(misses[i].our_sample);
      branch += d.dot(branch) < 0 ? -d : d;
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(cov / c.size());
    const Eigen::Vector3d l = pca.eigenvalues();  // ascending
    const double angle =
        std::acos(std::min(1.0, std::abs(pca.eigenvectors().col(2).dot(branch.normalized()))));
    const bool elongated = l(2) >= 9 * l(1) && 2 * std::sqrt(3 * l(2)) >= 3 * link_m;
    const bool leaves = angle >= 30 * M_PI / 180 || hi - lo >= 0.03;
    if (elongated && leaves)
      for (const int i : c) twig[i] = 1;
  }
  return twig;
}

// For the misses where the reference has wood apart from ours: was there a medial sample near the
// reference's axis, a grown node?
void PrintStages(const std::vector<Miss>& misses, const Stages& stages, size_t points) {
  const reconstruction::PointIndex samples(stages.samples), grown(stages.grown);
  std::vector<int> near;
  std::vector<double> d2;
  auto within = [&](const reconstruction::PointIndex& index, const Eigen::Vector3d& p, double r) {
    index.Nearest(p, 1, near, d2);
    return !near.empty() && d2[0] <= r * r;
  };
  int apart = 0, grown_there = 0, sampled_only = 0, none = 0;
  for (const Miss& m : misses) {
    if (!m.reference_apart) continue;
    ++apart;
    if (within(grown, m.reference_axis, stages.grown_near_m)) {
      ++grown_there;
    } else if (within(samples, m.reference_axis, stages.sample_near_m)) {
      ++sampled_only;
    } else {
      ++none;
    }
  }
  const double n = 100.0 / points;
  std::printf(
      "reference apart from our wood: %.1f%% of the points; the grown skeleton within %.1f cm of "
      "its axis (pruned or moved later): %.1f%%; else a medial sample within %.1f cm (never "
      "grown there): %.1f%%; neither (no sample: merged into another band piece): %.1f%%\n",
      n * apart, 100 * stages.grown_near_m, n * grown_there, 100 * stages.sample_near_m,
      n * sampled_only, n * none);
}

}  // namespace

void PrintMisses(const std::string& name, const Tree& ours, const Tree& reference,
                 std::span<const Eigen::Vector3d> points, double link_m, const Stages& stages) {
  const Axes our_axes(ours), ref_axes(reference);
  const std::vector<double> our_d = eval::SurfaceDistances(ours, points);
  const std::vector<double> ref_d = eval::SurfaceDistances(reference, points);
  const std::vector<Miss> misses = ClassifyMisses(our_axes, ref_axes, our_d, ref_d, points);
  const std::vector<char> twig = TwigPoints(misses, our_axes, points, link_m);
  struct Row {
    int all = 0, outside = 0, fits = 0, apart = 0, thicker = 0, twig = 0;
    std::vector<double> ratio;
  };
  std::vector<Row> rows(kBucketTops.size() + 1);
  for (size_t i = 0; i < misses.size(); ++i) {
    const Miss& m = misses[i];
    for (Row* r : {&rows[m.bucket], &rows.back()}) {
      ++r->all;
      r->outside += m.outside;
      r->fits += m.reference_fits;
      r->apart += m.reference_apart;
      r->thicker += m.reference_thicker;
      r->twig += twig[i];
      if (m.reference_fits && !m.reference_apart) r->ratio.push_back(m.radius_ratio);
    }
  }
  const double n = 100.0 / points.size();
  std::printf(
      "\n%s: %zu points, %zu (%.1f%%) 2-10 cm from the model (link %.1f cm)\n"
      "| our radius there | missed (of all points) | outside our wood | reference within 2 cm | "
      "reference axis outside our wood | reference same wood, >1.3x thicker | median "
      "reference/our radius (same wood) | in an elongated cluster leaving the branch |\n"
      "| --- | --- | --- | --- | --- | --- | --- | --- |\n",
      name.c_str(), points.size(), misses.size(), n * misses.size(), 100 * link_m);
  for (size_t b = 0; b < rows.size(); ++b) {
    Row& r = rows[b];
    double median = 0;
    if (!r.ratio.empty()) {
      std::nth_element(r.ratio.begin(), r.ratio.begin() + r.ratio.size() / 2, r.ratio.end());
      median = r.ratio[r.ratio.size() / 2];
    }
    std::printf("| %s | %.1f%% | %.1f%% | %.1f%% | %.1f%% | %.1f%% | %.2f | %.1f%% |\n",
                b < kBucketTops.size() ? kBucketNames[b] : "all", n * r.all, n * r.outside,
                n * r.fits, n * r.apart, n * r.thicker, median, n * r.twig);
  }
  PrintStages(misses, stages, points.size());
}

}  // namespace simtree::bench
