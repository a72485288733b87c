#include "simtree/registration/register.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>

#include <fmt/format.h>
#include <oneapi/tbb/parallel_for.h>

#include "simtree/core/error.h"
#include "simtree/core/interrupt.h"
#include "simtree/core/option_checks.h"
#include "simtree/registration/detail/pose_graph.h"

namespace simtree::registration {
namespace {

// Whether `result` (target_from_source of the pair source -> target) agrees with `chain` (the
// poses of the views the trusted pairs reach from `target`) within the wider tolerance of the
// unoptimised chain (MultiViewOptions::chained_decline_factor); "" when it does not or the chain
// does not reach the source, else the reason to decline.
std::string AgreesWithChain(const ChainedPoses& chain, const Eigen::Isometry3d& result,
                            const RegistrationView& source_view, int source,
                            const MultiViewOptions& options) {
  if (!chain.anchor_from_view[source]) return "";
  const PoseDifference d =
      DifferenceAt(chain.anchor_from_view[source]->inverse() * result, source_view);
  if (d.rotation_deg > options.chained_decline_factor * options.max_pair_rotation_deg ||
      d.shift_m > options.chained_decline_factor * options.max_pair_shift_m) {
    return "";
  }
  return fmt::format("its result agrees with the trusted pairs' chain ({:.1f} deg, {:.0f} mm)",
                     d.rotation_deg, 1e3 * d.shift_m);
}

// A pair whose first result failed for too little overlap but agrees with the chain of the pairs
// trusted at their first attempt between its two views is right, only seen from views too far
// apart to overlap more: its retries would find the same result again (on the synthetic
// captures they always did). It is declined without them; the chain's poses are not yet
// optimised, hence the wider tolerance (MultiViewOptions::chained_decline_factor).
void DeclineChainedPairs(const std::vector<RegistrationView>& views,
                         const MultiViewOptions& options, std::vector<PairEdge>& pairs) {
  if (!(options.chained_decline_factor > 0)) return;
  std::vector<char> trusted(pairs.size());
  for (size_t e = 0; e < pairs.size(); ++e) trusted[e] = pairs[e].result.ok();
  const int n = static_cast<int>(views.size());
  for (PairEdge& edge : pairs) {
    const PairResult& r = edge.result;
    if (r.ok() || !r.declined.empty() || r.attempts.empty() || !r.attempts.front().refined ||
        r.fine.fitness >= options.pair.min_fitness) {
      continue;
    }
    const std::string agrees =
        AgreesWithChain(ChainPoses(pairs, trusted, n, edge.target), r.target_from_source,
                        views[edge.source], edge.source, options);
    if (!agrees.empty()) DeclinePair("declined without retries: " + agrees, edge.result);
  }
}

// Neighbours around the ring first: their trusted pairs chain the views together, so that the
// pairs between views further apart, which overlap less, can be declined before their turn
// screen when their first result already agrees with that chain (the screen is most of such a
// pair's time, and it finds nothing better for a right result).
bool IsNeighbourPair(const PairEdge& edge, int view_count) {
  const int gap = std::abs(edge.source - edge.target);
  return gap == 1 || gap == view_count - 1;
}

// The screen gate of the pairs registered after the neighbours (RegisterPairFirstAttempt): a
// result overlapping less than min_fitness that agrees with the neighbours' chain is declined.
ScreenGate ChainGate(const std::vector<ChainedPoses>& chains, const RegistrationView& source_view,
                     const PairEdge& edge, const MultiViewOptions& options) {
  return [&chains, &source_view, &options, source = edge.source, target = edge.target](
             const Eigen::Isometry3d& result, double view_overlap) -> std::string {
    if (view_overlap >= options.pair.min_fitness) return "";
    const std::string agrees =
        AgreesWithChain(chains[target], result, source_view, source, options);
    return agrees.empty() ? "" : "declined without its turn screen and retries: " + agrees;
  };
}

// First attempts of `which` pairs, all at once (each pair's ICP is parallel too); Ctrl-C stops
// between pairs (TBB carries the exception out of the loop).
void RunFirstAttempts(const std::vector<RegistrationView>& views, const MultiViewOptions& options,
                      const std::vector<size_t>& which, const std::vector<ChainedPoses>* chains,
                      std::vector<PairEdge>& pairs) {
  oneapi::tbb::parallel_for(size_t{0}, which.size(), [&](size_t i) {
    ThrowIfInterrupted();
    PairEdge& edge = pairs[which[i]];
    const ScreenGate gate =
        chains ? ChainGate(*chains, views[edge.source], edge, options) : ScreenGate{};
    edge.result =
        RegisterPairFirstAttempt(views[edge.source], views[edge.target], options.pair, gate);
  });
}

// Every pair around the ring (ViewPairs), each registered on its own: the neighbours' first
// attempts, the others' (declined before their screen where the neighbours' chain says they
// are right), then the retries of the pairs not declined.
std::vector<PairEdge> RegisterViewPairs(const std::vector<RegistrationView>& views,
                                        const MultiViewOptions& options) {
  const int n = static_cast<int>(views.size());
  std::vector<PairEdge> pairs;
  std::vector<size_t> neighbours, others;
  for (const auto& [s, t] : ViewPairs(n, options)) {
    PairEdge edge;
    edge.source = s;
    edge.target = t;
    (IsNeighbourPair(edge, n) ? neighbours : others).push_back(pairs.size());
    pairs.push_back(edge);
  }
  RunFirstAttempts(views, options, neighbours, nullptr, pairs);
  std::vector<ChainedPoses> chains;
  if (options.chained_decline_factor > 0 && !others.empty()) {
    std::vector<char> trusted(pairs.size(), 0);
    for (const size_t e : neighbours) trusted[e] = pairs[e].result.ok();
    for (int v = 0; v < n; ++v) chains.push_back(ChainPoses(pairs, trusted, n, v));
  }
  RunFirstAttempts(views, options, others, chains.empty() ? nullptr : &chains, pairs);
  DeclineChainedPairs(views, options, pairs);
  oneapi::tbb::parallel_for(size_t{0}, pairs.size(), [&](size_t e) {
    ThrowIfInterrupted();
    PairEdge& edge = pairs[e];
    RetryPair(views[edge.source], views[edge.target], options.pair, edge.result);
  });
  return pairs;
}

// The anchor: the one asked for, else the view with the most trusted pairs (ties: the first).
int ChooseAnchor(const std::vector<PairEdge>& pairs, int view_count, int requested) {
  if (requested >= 0) return requested;
  std::vector<int> degree(view_count, 0);
  for (const PairEdge& edge : pairs) {
    if (!edge.result.ok()) continue;
    ++degree[edge.source];
    ++degree[edge.target];
  }
  return static_cast<int>(std::max_element(degree.begin(), degree.end()) - degree.begin());
}

// Why view `v`, which no consistent pair links, was left out: the first reason of its own pairs.
std::string WhyNotLinked(const std::vector<RegistrationView>& views,
                         const std::vector<PairEdge>& pairs, int v) {
  std::string reason = "no trusted pair links it to the other views";
  for (const PairEdge& edge : pairs) {
    if ((edge.source == v || edge.target == v) && !edge.result.ok()) {
      reason +=
          fmt::format(" (with {}: {})", views[edge.source == v ? edge.target : edge.source].name,
                      edge.result.status);
      break;
    }
  }
  return reason;
}

// Each view's outcome and, when registered, its pose in the registration frame: a view is
// registered when a trusted, consistent pair links it to the anchor, verified when two do.
std::vector<ViewRegistration> JudgeViews(
    const std::vector<RegistrationView>& views, const std::vector<PairEdge>& pairs,
    const std::vector<std::optional<Eigen::Isometry3d>>& anchor_from_view,
    const Eigen::Isometry3d& frame_from_anchor) {
  const int n = static_cast<int>(views.size());
  std::vector<ViewRegistration> out(n);
  for (const PairEdge& edge : pairs) {
    if (!edge.used || !edge.consistent) continue;
    ++out[edge.source].pairs;
    ++out[edge.target].pairs;
  }
  for (int v = 0; v < n; ++v) {
    ViewRegistration& view = out[v];
    view.name = views[v].name;
    if (!views[v].CanRegister()) {
      view.outcome = ViewOutcome::kCannotRegister;
      view.status = views[v].failure;
    } else if (n == 1) {
      view.outcome = ViewOutcome::kOnlyView;
    } else if (!anchor_from_view[v] || view.pairs == 0) {
      view.outcome = ViewOutcome::kNotLinked;
      view.status = WhyNotLinked(views, pairs, v);
    } else {
      view.outcome = view.pairs >= 2 ? ViewOutcome::kVerified : ViewOutcome::kOnePair;
    }
    if (view.registered()) {
      view.status = ToString(view.outcome);
      view.frame_from_camera = frame_from_anchor * *anchor_from_view[v];
    }
  }
  return out;
}

// The registered views in the registration frame, one point per voxel of `voxel_factor` times
// the largest point spacing among them.
open3d::geometry::PointCloud MergeViews(const std::vector<RegistrationView>& views,
                                        const std::vector<ViewRegistration>& registered,
                                        double voxel_factor) {
  open3d::geometry::PointCloud merged;
  double spacing = 0.0;
  for (size_t v = 0; v < views.size(); ++v) {
    if (!registered[v].registered()) continue;
    open3d::geometry::PointCloud cloud = *views[v].cloud;
    cloud.Transform(registered[v].frame_from_camera.matrix());
    merged += cloud;
    spacing = std::max(spacing, views[v].spacing_m);
  }
  if (spacing > 0 && !merged.points_.empty()) {
    merged = *merged.VoxelDownSample(voxel_factor * spacing);
  }
  return merged;
}

}  // namespace

void MultiViewOptions::Validate() const {
  CheckNested("pair", [&] { pair.Validate(); });
  CheckAtLeast("neighbour_span", neighbour_span, 1);
  CheckAtLeast("anchor", anchor, -1);
  CheckPositive("information_distance_factor", information_distance_factor);
  CheckShare("edge_prune_threshold", edge_prune_threshold);
  CheckPositive("max_pair_rotation_deg", max_pair_rotation_deg);
  CheckPositive("max_pair_shift_m", max_pair_shift_m);
  CheckPositive("merge_voxel_factor", merge_voxel_factor);
  CheckNonNegative("chained_decline_factor", chained_decline_factor);
}

const char* ToString(ViewOutcome outcome) {
  switch (outcome) {
    case ViewOutcome::kVerified:
      return "ok";
    case ViewOutcome::kOnePair:
      return "ok (one pair only: not checked by a loop)";
    case ViewOutcome::kOnlyView:
      return "ok (the only view)";
    case ViewOutcome::kCannotRegister:
      return "cannot be registered";
    case ViewOutcome::kNotLinked:
      return "no trusted pair links it to the other views";
  }
  return "?";
}

bool ViewRegistration::registered() const {
  return outcome == ViewOutcome::kVerified || outcome == ViewOutcome::kOnePair ||
         outcome == ViewOutcome::kOnlyView;
}

int MultiViewResult::RegisteredCount() const {
  return static_cast<int>(
      std::count_if(views.begin(), views.end(), [](const auto& v) { return v.registered(); }));
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
  options.Validate();
  const int n = static_cast<int>(views.size());
  if (options.anchor >= n && n > 0) {
    throw InputError("options", "anchor",
                     fmt::format("expected a view index below {}, got {}", n, options.anchor));
  }
  const auto start = std::chrono::steady_clock::now();
  MultiViewResult result;
  result.views.resize(n);
  for (int v = 0; v < n; ++v) result.views[v].name = views[v].name;
  if (n == 0) return result;

  // Pairs around the ring (and loop closures), each on its own; its checks say if it is trusted.
  result.pairs = RegisterViewPairs(views, options);
  for (const PairEdge& edge : result.pairs) result.pair_seconds += edge.result.seconds;
  result.anchor = ChooseAnchor(result.pairs, n, options.anchor);
  // One pose per view from the trusted pairs, dropping those the others contradict.
  PoseGraphSolution graph = SolvePoseGraph(views, std::move(result.pairs), result.anchor, options);
  result.pairs = std::move(graph.pairs);
  // The registration frame stands upright on the anchor's ground, at the foot of its trunk.
  result.frame_from_anchor = UprightFrameOf(views[result.anchor]);
  result.views = JudgeViews(views, result.pairs, graph.anchor_from_view, result.frame_from_anchor);
  result.merged = MergeViews(views, result.views, options.merge_voxel_factor);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace simtree::registration
