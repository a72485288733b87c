#pragma once
// All views of a capture in one frame: pairwise registration between neighbouring views around
// the tree plus loop closures, a pose graph optimised over every trusted pair (Open3D's
// GlobalOptimization, whose line process prunes a bad loop closure), and a consistency check of
// every pair against the optimised poses. A view is registered only when a trusted, consistent
// pair links it to the anchor view; the others are reported and left out of the merged cloud.
//
// The output frame ("registration frame") is the anchor view's, turned so that Z is up (its
// ground's normal, else its trunk's axis) and moved so that the origin is the foot of the trunk
// on the ground: the frame a static tree is built in.
//
// Usage (views prepared from preprocessed clouds, registration_view.h):
//   std::vector<simtree::registration::RegistrationView> views;
//   for (const auto& v : simtree::preprocessing::LoadViews("scene/"))
//     if (v.result) views.push_back(simtree::registration::PrepareView(v.name, *v.result));
//   const simtree::registration::MultiViewResult result =
//       simtree::registration::RegisterViews(views, {});
//   // result.views[i].frame_from_camera: each view's pose; result.merged: the merged cloud

#include <string>
#include <vector>

#include <open3d/geometry/PointCloud.h>
#include <Eigen/Geometry>

#include "simtree/registration/detail/pairwise.h"
#include "simtree/registration/registration_view.h"

namespace simtree::registration {

struct MultiViewOptions {
  PairOptions pair;
  // Each view is paired with the next `neighbour_span` views (1: neighbours only, 2: also every
  // second one, which closes small loops). Views are taken in their order around the tree.
  int neighbour_span = 2;
  // The last view is a neighbour of the first (a capture all around the tree).
  bool closed_ring = true;
  // The anchor view (its index); -1: the view with the most trusted pairs.
  int anchor = -1;
  // Pose graph: correspondence distance for the pairs' information matrices, in point spacings.
  double information_distance_factor = 1.5;
  double edge_prune_threshold = 0.25;
  // After optimisation a pair is inconsistent when its own result and the optimised poses differ
  // by more than this rotation or move its source's key region by more than this distance.
  double max_pair_rotation_deg = 1.5;
  double max_pair_shift_m = 0.025;
  // The merged cloud is thinned to one point per voxel of this many point spacings.
  double merge_voxel_factor = 1.0;
};

struct ViewRegistration {
  std::string name;
  bool registered = false;
  bool verified = false;  // in a loop of consistent pairs (not a dangling chain)
  std::string status;     // "ok", or why the view was left out
  Eigen::Isometry3d frame_from_camera = Eigen::Isometry3d::Identity();
  int pairs = 0;  // trusted, consistent pairs it takes part in
};

struct PairEdge {
  int source = 0, target = 0;  // view indices
  PairResult result;
  bool used = false;        // trusted by its own checks, in the pose graph
  bool consistent = false;  // agrees with the optimised poses
  double rotation_residual_deg = 0.0;
  double shift_residual_m = 0.0;
};

struct MultiViewResult {
  std::vector<ViewRegistration> views;
  std::vector<PairEdge> pairs;
  int anchor = 0;
  Eigen::Isometry3d frame_from_anchor = Eigen::Isometry3d::Identity();
  open3d::geometry::PointCloud merged;  // registered views in the registration frame, thinned
  double seconds = 0.0;
  double pair_seconds = 0.0;  // sum over pairs (coarse + fine)
  int RegisteredCount() const;
};

// The pairs RegisterViews would register, as (source, target) view indices.
std::vector<std::pair<int, int>> ViewPairs(int view_count, const MultiViewOptions& options);

MultiViewResult RegisterViews(const std::vector<RegistrationView>& views,
                              const MultiViewOptions& options = {});

// The registration frame of a view: its camera frame turned so that up is +Z and the camera looks
// along +Y, the foot of its trunk (or its cloud's lowest point under its centre) at the origin.
Eigen::Isometry3d UprightFrameOf(const RegistrationView& view);

}  // namespace simtree::registration
