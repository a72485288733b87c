#include "simtree/registration/register.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <set>

#include <fmt/format.h>
#include <oneapi/tbb/parallel_for.h>
#include <open3d/pipelines/registration/GlobalOptimization.h>
#include <open3d/pipelines/registration/PoseGraph.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/utility/Logging.h>

namespace simtree::registration {
namespace {

namespace reg = open3d::pipelines::registration;

double RotationDeg(const Eigen::Isometry3d& t) {
  return std::abs(Eigen::AngleAxisd(t.linear()).angle()) * 180.0 / std::numbers::pi;
}

// A point that stands for where a view's tree is (its key region's centre, else its centroid).
Eigen::Vector3d LeverPoint(const RegistrationView& view) {
  if (view.key_region) return view.key_region->center;
  return view.cloud ? view.cloud->GetCenter() : Eigen::Vector3d::Zero();
}

// Poses (anchor_from_view) of the views reachable from `anchor` through `usable` pairs, taking
// the best-matching pair into the known set first. Unreached views stay nullopt.
std::vector<std::optional<Eigen::Isometry3d>> ChainPoses(const std::vector<PairEdge>& pairs,
                                                         const std::vector<char>& usable,
                                                         int view_count, int anchor,
                                                         std::vector<char>& in_tree) {
  std::vector<std::optional<Eigen::Isometry3d>> poses(view_count);
  poses[anchor] = Eigen::Isometry3d::Identity();
  in_tree.assign(pairs.size(), 0);
  for (;;) {
    int best = -1;
    for (size_t e = 0; e < pairs.size(); ++e) {
      if (!usable[e]) continue;
      const bool s = poses[pairs[e].source].has_value(), t = poses[pairs[e].target].has_value();
      if (s == t) continue;
      if (best < 0 || pairs[e].result.match_rate > pairs[best].result.match_rate) best = e;
    }
    if (best < 0) break;
    const PairEdge& edge = pairs[best];
    const Eigen::Isometry3d& t_from_s = edge.result.target_from_source;
    if (poses[edge.target]) {
      poses[edge.source] = *poses[edge.target] * t_from_s;
    } else {
      poses[edge.target] = *poses[edge.source] * t_from_s.inverse();
    }
    in_tree[best] = 1;
  }
  return poses;
}

}  // namespace

int MultiViewResult::RegisteredCount() const {
  return static_cast<int>(
      std::count_if(views.begin(), views.end(), [](const auto& v) { return v.registered; }));
}

std::vector<std::pair<int, int>> ViewPairs(int view_count, const MultiViewOptions& options) {
  std::vector<std::pair<int, int>> pairs;
  std::set<std::pair<int, int>> seen;
  // Beyond view_count - 1 apart every pair has come up already.
  const int span = std::min(std::max(1, options.neighbour_span), view_count - 1);
  for (int k = 1; k <= span; ++k) {
    for (int i = 0; i < view_count; ++i) {
      int j = i + k;
      if (j >= view_count) {
        if (!options.closed_ring) continue;
        j -= view_count;
      }
      const auto key = std::minmax(i, j);
      if (!seen.insert(key).second) continue;
      pairs.emplace_back(j, i);  // source j into target i
    }
  }
  return pairs;
}

Eigen::Isometry3d UprightFrameOf(const RegistrationView& view) {
  const Eigen::Vector3d up =
      view.ground ? view.ground->normal.normalized() : TrunkAxis(view).normalized();
  Eigen::Vector3d forward = Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ().dot(up) * up;
  if (forward.norm() < 1e-6) forward = up.unitOrthogonal();
  forward.normalize();
  const Eigen::Vector3d right = forward.cross(up);
  Eigen::Matrix3d rotation;
  rotation.row(0) = right.transpose();
  rotation.row(1) = forward.transpose();
  rotation.row(2) = up.transpose();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  if (view.trunk) {
    origin = view.trunk->base;
  } else if (view.cloud && !view.cloud->points_.empty()) {
    origin = view.cloud->GetCenter();
    double lowest = std::numeric_limits<double>::infinity();
    for (const auto& p : view.cloud->points_) lowest = std::min(lowest, p.dot(up));
    origin += (lowest - origin.dot(up)) * up;
  }
  if (view.ground) origin -= view.ground->SignedDistance(origin) * view.ground->normal;
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  frame.linear() = rotation;
  frame.translation() = -(rotation * origin);
  return frame;
}

MultiViewResult RegisterViews(const std::vector<RegistrationView>& views,
                              const MultiViewOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  MultiViewResult result;
  const int n = static_cast<int>(views.size());
  result.views.resize(n);
  for (int v = 0; v < n; ++v) result.views[v].name = views[v].name;
  if (n == 0) return result;

  // Pairwise registration, every pair at once (each pair's ICP is parallel too).
  for (const auto& [s, t] : ViewPairs(n, options)) {
    PairEdge edge;
    edge.source = s;
    edge.target = t;
    result.pairs.push_back(edge);
  }
  oneapi::tbb::parallel_for(size_t{0}, result.pairs.size(), [&](size_t e) {
    PairEdge& edge = result.pairs[e];
    edge.result = RegisterPair(views[edge.source], views[edge.target], options.pair);
  });
  std::vector<char> usable(result.pairs.size());
  for (size_t e = 0; e < result.pairs.size(); ++e) {
    usable[e] = result.pairs[e].result.ok;
    result.pair_seconds += result.pairs[e].result.seconds;
  }

  // The anchor: the view with the most trusted pairs (ties: the first).
  if (options.anchor >= 0 && options.anchor < n) {
    result.anchor = options.anchor;
  } else {
    std::vector<int> degree(n, 0);
    for (size_t e = 0; e < result.pairs.size(); ++e) {
      if (!usable[e]) continue;
      ++degree[result.pairs[e].source];
      ++degree[result.pairs[e].target];
    }
    result.anchor =
        static_cast<int>(std::max_element(degree.begin(), degree.end()) - degree.begin());
  }

  // Optimise, then drop the worst inconsistent pair and optimise again, until all agree.
  std::vector<std::optional<Eigen::Isometry3d>> poses;
  for (int round = 0; round <= static_cast<int>(result.pairs.size()); ++round) {
    std::vector<char> in_tree;
    poses = ChainPoses(result.pairs, usable, n, result.anchor, in_tree);
    // Pose graph over the reached views.
    std::vector<int> node_of(n, -1), view_of;
    for (int v = 0; v < n; ++v) {
      if (!poses[v]) continue;
      node_of[v] = static_cast<int>(view_of.size());
      view_of.push_back(v);
    }
    reg::PoseGraph graph;
    for (int v : view_of) graph.nodes_.emplace_back(poses[v]->matrix());
    int loop_edges = 0;
    for (size_t e = 0; e < result.pairs.size(); ++e) {
      const PairEdge& edge = result.pairs[e];
      if (!usable[e] || node_of[edge.source] < 0 || node_of[edge.target] < 0) continue;
      const RegistrationView& s = views[edge.source];
      const RegistrationView& t = views[edge.target];
      const double distance =
          options.information_distance_factor * std::max(s.spacing_m, t.spacing_m);
      const Eigen::Matrix6d information = reg::GetInformationMatrixFromPointClouds(
          *s.cloud, *t.cloud, distance, edge.result.target_from_source.matrix());
      graph.edges_.emplace_back(node_of[edge.source], node_of[edge.target],
                                edge.result.target_from_source.matrix(), information,
                                /*uncertain=*/!in_tree[e]);
      if (!in_tree[e]) ++loop_edges;
    }
    if (loop_edges > 0) {
      const double distance = options.information_distance_factor * views[result.anchor].spacing_m;
      const auto verbosity = open3d::utility::GetVerbosityLevel();
      open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);
      reg::GlobalOptimization(graph, reg::GlobalOptimizationLevenbergMarquardt(),
                              reg::GlobalOptimizationConvergenceCriteria(),
                              reg::GlobalOptimizationOption(distance, options.edge_prune_threshold,
                                                            1.0, node_of[result.anchor]));
      open3d::utility::SetVerbosityLevel(verbosity);
      for (size_t k = 0; k < view_of.size(); ++k) {
        poses[view_of[k]] = Eigen::Isometry3d(graph.nodes_[k].pose_);
      }
    }

    // Every trusted pair against the optimised poses.
    int worst = -1;
    double worst_excess = 0.0;
    for (size_t e = 0; e < result.pairs.size(); ++e) {
      PairEdge& edge = result.pairs[e];
      edge.used = usable[e];
      edge.consistent = false;
      if (!usable[e] || !poses[edge.source] || !poses[edge.target]) continue;
      const Eigen::Isometry3d predicted = poses[edge.target]->inverse() * *poses[edge.source];
      const Eigen::Isometry3d error = predicted.inverse() * edge.result.target_from_source;
      const Eigen::Vector3d lever = LeverPoint(views[edge.source]);
      edge.rotation_residual_deg = RotationDeg(error);
      edge.shift_residual_m = (error * lever - lever).norm();
      const double excess = std::max(edge.rotation_residual_deg / options.max_pair_rotation_deg,
                                     edge.shift_residual_m / options.max_pair_shift_m);
      edge.consistent = excess <= 1.0;
      if (!edge.consistent && excess > worst_excess) {
        worst_excess = excess;
        worst = static_cast<int>(e);
      }
    }
    if (worst < 0) break;
    usable[worst] = 0;
    result.pairs[worst].used = false;
  }

  // Views: registered when a consistent pair links them to the anchor.
  for (size_t e = 0; e < result.pairs.size(); ++e) {
    const PairEdge& edge = result.pairs[e];
    if (!edge.used || !edge.consistent) continue;
    ++result.views[edge.source].pairs;
    ++result.views[edge.target].pairs;
  }
  result.frame_from_anchor = UprightFrameOf(views[result.anchor]);
  for (int v = 0; v < n; ++v) {
    ViewRegistration& view = result.views[v];
    if (!views[v].CanRegister()) {
      view.status = views[v].failure;
    } else if (n == 1) {
      view.registered = true;
      view.status = "ok (the only view)";
    } else if (!poses[v] || view.pairs == 0) {
      // Say why: the first reason of its own pairs.
      std::string reason = "no trusted pair links it to the other views";
      for (const PairEdge& edge : result.pairs) {
        if ((edge.source == v || edge.target == v) && !edge.result.ok) {
          reason += fmt::format(" (with {}: {})",
                                views[edge.source == v ? edge.target : edge.source].name,
                                edge.result.status);
          break;
        }
      }
      view.status = reason;
    } else {
      view.registered = true;
      view.verified = view.pairs >= 2;
      view.status = view.verified ? "ok" : "ok (one pair only: not checked by a loop)";
    }
    if (view.registered) view.frame_from_camera = result.frame_from_anchor * *poses[v];
  }

  // The merged cloud.
  double spacing = 0.0;
  for (int v = 0; v < n; ++v) {
    if (!result.views[v].registered) continue;
    open3d::geometry::PointCloud cloud = *views[v].cloud;
    cloud.Transform(result.views[v].frame_from_camera.matrix());
    result.merged += cloud;
    spacing = std::max(spacing, views[v].spacing_m);
  }
  if (spacing > 0 && !result.merged.points_.empty()) {
    result.merged = *result.merged.VoxelDownSample(options.merge_voxel_factor * spacing);
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace simtree::registration
