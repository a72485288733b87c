#pragma once
// The views' poses from their registered pairs (RegisterViews, register.h): the trusted pairs
// chained from the anchor view, then optimised as a pose graph (Open3D's GlobalOptimization,
// whose line process prunes a bad loop closure). A pair that disagrees with the optimised poses
// is dropped, the worst first, and the graph optimised again, until every pair left agrees: one
// wrong pair must not bend the others.

#include <optional>
#include <vector>

#include <Eigen/Geometry>

#include "simtree/registration/register.h"

namespace simtree::registration {

struct PoseGraphSolution {
  // anchor_from_view of every view a trusted pair chain reaches from the anchor; nullopt else.
  std::vector<std::optional<Eigen::Isometry3d>> anchor_from_view;
  std::vector<PairEdge> pairs;  // the pairs given, with used, consistent and residuals set
};

// `pairs` as registered (PairEdge::result); a pair is trusted when its result is ok.
PoseGraphSolution SolvePoseGraph(const std::vector<RegistrationView>& views,
                                 std::vector<PairEdge> pairs, int anchor,
                                 const MultiViewOptions& options);

// A point that stands for where a view's tree is, not its camera: its key region's centre, else
// its centroid.
Eigen::Vector3d LeverPoint(const RegistrationView& view);

// How far apart two poses of one view are, from `error` (one pose's inverse times the other):
// the angle of its rotation, and how far it moves the view's lever point.
struct PoseDifference {
  double rotation_deg = 0.0;
  double shift_m = 0.0;
};
PoseDifference DifferenceAt(const Eigen::Isometry3d& error, const RegistrationView& view);

// Poses (anchor_from_view) of the views reachable from `anchor` through the `usable` pairs, the
// best-matching pair (PairResult::match_rate) into the known set first; unreached views stay
// nullopt. `in_tree` marks the pairs the chain took.
struct ChainedPoses {
  std::vector<std::optional<Eigen::Isometry3d>> anchor_from_view;
  std::vector<char> in_tree;
};
ChainedPoses ChainPoses(const std::vector<PairEdge>& pairs, const std::vector<char>& usable,
                        int view_count, int anchor);

}  // namespace simtree::registration
