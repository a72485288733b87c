#include "simtree/registration/detail/pose_graph.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <open3d/pipelines/registration/GlobalOptimization.h>
#include <open3d/pipelines/registration/PoseGraph.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/utility/Logging.h>

namespace simtree::registration {
namespace {

namespace reg = open3d::pipelines::registration;

// The chained poses refined as a pose graph over the usable pairs between reached views, when
// the graph holds a loop (a pair the chain did not take).
std::vector<std::optional<Eigen::Isometry3d>> OptimisePoses(
    const std::vector<RegistrationView>& views, const std::vector<PairEdge>& pairs,
    const std::vector<char>& usable, const ChainedPoses& chained, int anchor,
    const MultiViewOptions& options) {
  std::vector<std::optional<Eigen::Isometry3d>> poses = chained.anchor_from_view;
  const int n = static_cast<int>(views.size());
  std::vector<int> node_of(n, -1), view_of;
  for (int v = 0; v < n; ++v) {
    if (!poses[v]) continue;
    node_of[v] = static_cast<int>(view_of.size());
    view_of.push_back(v);
  }
  reg::PoseGraph graph;
  for (int v : view_of) graph.nodes_.emplace_back(poses[v]->matrix());
  int loop_edges = 0;
  for (size_t e = 0; e < pairs.size(); ++e) {
    const PairEdge& edge = pairs[e];
    if (!usable[e] || node_of[edge.source] < 0 || node_of[edge.target] < 0) continue;
    const RegistrationView& s = views[edge.source];
    const RegistrationView& t = views[edge.target];
    const double distance =
        options.information_distance_factor * std::max(s.spacing_m, t.spacing_m);
    const Eigen::Matrix6d information = reg::GetInformationMatrixFromPointClouds(
        *s.cloud, *t.cloud, distance, edge.result.target_from_source.matrix());
    graph.edges_.emplace_back(node_of[edge.source], node_of[edge.target],
                              edge.result.target_from_source.matrix(), information,
                              /*uncertain=*/!chained.in_tree[e]);
    if (!chained.in_tree[e]) ++loop_edges;
  }
  if (loop_edges == 0) return poses;
  const double distance = options.information_distance_factor * views[anchor].spacing_m;
  const auto verbosity = open3d::utility::GetVerbosityLevel();
  open3d::utility::SetVerbosityLevel(open3d::utility::VerbosityLevel::Error);
  reg::GlobalOptimization(
      graph, reg::GlobalOptimizationLevenbergMarquardt(),
      reg::GlobalOptimizationConvergenceCriteria(),
      reg::GlobalOptimizationOption(distance, options.edge_prune_threshold, 1.0, node_of[anchor]));
  open3d::utility::SetVerbosityLevel(verbosity);
  for (size_t k = 0; k < view_of.size(); ++k) {
    poses[view_of[k]] = Eigen::Isometry3d(graph.nodes_[k].pose_);
  }
  return poses;
}

// Every usable pair against the poses: its residuals and whether it agrees with them. Returns
// the pair that disagrees most (by its residuals over their limits), -1 when every one agrees.
int JudgePairs(const std::vector<RegistrationView>& views,
               const std::vector<std::optional<Eigen::Isometry3d>>& poses,
               const std::vector<char>& usable, const MultiViewOptions& options,
               std::vector<PairEdge>& pairs) {
  int worst = -1;
  double worst_excess = 0.0;
  for (size_t e = 0; e < pairs.size(); ++e) {
    PairEdge& edge = pairs[e];
    edge.used = usable[e];
    edge.consistent = false;
    if (!usable[e] || !poses[edge.source] || !poses[edge.target]) continue;
    const Eigen::Isometry3d predicted = poses[edge.target]->inverse() * *poses[edge.source];
    const PoseDifference difference =
        DifferenceAt(predicted.inverse() * edge.result.target_from_source, views[edge.source]);
    edge.rotation_residual_deg = difference.rotation_deg;
    edge.shift_residual_m = difference.shift_m;
    const double excess = std::max(edge.rotation_residual_deg / options.max_pair_rotation_deg,
                                   edge.shift_residual_m / options.max_pair_shift_m);
    edge.consistent = excess <= 1.0;
    if (!edge.consistent && excess > worst_excess) {
      worst_excess = excess;
      worst = static_cast<int>(e);
    }
  }
  return worst;
}

}  // namespace

Eigen::Vector3d LeverPoint(const RegistrationView& view) {
  if (view.key_region) return view.key_region->center;
  return view.cloud ? view.cloud->GetCenter() : Eigen::Vector3d::Zero();
}

PoseDifference DifferenceAt(const Eigen::Isometry3d& error, const RegistrationView& view) {
  const Eigen::Vector3d lever = LeverPoint(view);
  return {std::abs(Eigen::AngleAxisd(error.linear()).angle()) * 180.0 / std::numbers::pi,
          (error * lever - lever).norm()};
}

ChainedPoses ChainPoses(const std::vector<PairEdge>& pairs, const std::vector<char>& usable,
                        int view_count, int anchor) {
  ChainedPoses chained;
  std::vector<std::optional<Eigen::Isometry3d>>& poses = chained.anchor_from_view;
  poses.resize(view_count);
  poses[anchor] = Eigen::Isometry3d::Identity();
  chained.in_tree.assign(pairs.size(), 0);
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
    chained.in_tree[best] = 1;
  }
  return chained;
}

PoseGraphSolution SolvePoseGraph(const std::vector<RegistrationView>& views,
                                 std::vector<PairEdge> pairs, int anchor,
                                 const MultiViewOptions& options) {
  const int n = static_cast<int>(views.size());
  std::vector<char> usable(pairs.size());
  for (size_t e = 0; e < pairs.size(); ++e) usable[e] = pairs[e].result.ok();
  PoseGraphSolution solution;
  // Each round drops the pair that disagrees most; there are at most as many rounds as pairs.
  for (size_t round = 0; round <= pairs.size(); ++round) {
    const ChainedPoses chained = ChainPoses(pairs, usable, n, anchor);
    solution.anchor_from_view = OptimisePoses(views, pairs, usable, chained, anchor, options);
    const int worst = JudgePairs(views, solution.anchor_from_view, usable, options, pairs);
    if (worst < 0) break;
    usable[worst] = 0;
    pairs[worst].used = false;
  }
  solution.pairs = std::move(pairs);
  return solution;
}

}  // namespace simtree::registration
