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
//   namespace reg = simtree::registration;
//   const std::vector<reg::RegistrationView> views =
//       reg::PrepareViews(simtree::preprocessing::LoadViews("scene/"));
//   const reg::MultiViewResult result = reg::RegisterViews(views, {});
//   // result.views[i].frame_from_camera: each registered view's pose; result.merged: the
//   // merged cloud; result.pairs: every pair with its checks.

#include <string>
#include <vector>

#include <open3d/geometry/PointCloud.h>
#include <Eigen/Geometry>

#include "simtree/registration/detail/pairwise.h"
#include "simtree/registration/registration_view.h"

namespace simtree::registration {

struct MultiViewOptions {
  PairOptions pair;  // every pair's registration and checks (pairwise.h)
  // >= 1: each view is paired with the next `neighbour_span` views (1: neighbours only, 2: also
  // every second one, which closes small loops). Views are taken in their order around the tree.
  int neighbour_span = 2;
  bool closed_ring = true;  // the last view is a neighbour of the first (a capture all around)
  int anchor = -1;  // the anchor view's index, below the view count (-1: the most trusted pairs)
  // Point spacings, > 0: the correspondence distance of the pairs' information matrices.
  double information_distance_factor = 1.5;
  double edge_prune_threshold = 0.25;  // [0, 1]: Open3D's line process prunes loop edges below
  // A pair disagrees with the optimised poses when its own result and theirs differ by more than
  // this rotation, or move its source's key region by more than this distance.
  double max_pair_rotation_deg = 1.5;  // deg, > 0
  double max_pair_shift_m = 0.025;     // m, > 0
  double merge_voxel_factor = 1.0;     // point spacings, > 0: the merged cloud's voxel grid
  // >= 0 (0: never): a pair whose first attempt overlaps too little but lands within this many
  // times max_pair_rotation_deg and max_pair_shift_m of the chain of pairs trusted at their first
  // attempt is declined without its retries (they find the same result again: views too far
  // apart around the tree to overlap more). Pairs of views further apart than neighbours are
  // registered after the neighbours and checked against the neighbours' chain before their turn
  // screen, most of such a pair's time.
  double chained_decline_factor = 2.0;

  // Throws InputError naming the field of a nonsense value (pair.sac_ia.iterations, ...).
  void Validate() const;
};

// How a view ended.
enum class ViewOutcome {
  kVerified,        // "ok": registered, in a loop of consistent pairs
  kOnePair,         // "ok (one pair only: not checked by a loop)": registered, not verified
  kOnlyView,        // "ok (the only view)": registered, there is nothing to pair it with
  kCannotRegister,  // left out: the view itself cannot be registered (RegistrationView::failure)
  kNotLinked,       // left out: no trusted, consistent pair links it to the other views
};
const char* ToString(ViewOutcome outcome);

struct ViewRegistration {
  std::string name;
  ViewOutcome outcome = ViewOutcome::kNotLinked;
  std::string status;  // "ok", or why the view was left out (poses.json, pairs.md)
  Eigen::Isometry3d frame_from_camera = Eigen::Isometry3d::Identity();  // when registered
  int pairs = 0;  // trusted, consistent pairs it takes part in

  bool registered() const;
  bool verified() const { return outcome == ViewOutcome::kVerified; }
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

// Throws InputError for nonsense options (an anchor that is no view's index included).
MultiViewResult RegisterViews(const std::vector<RegistrationView>& views,
                              const MultiViewOptions& options = {});

// The registration frame of a view: its camera frame turned so that up is +Z and the camera looks
// along +Y, the foot of its trunk (or its cloud's lowest point under its centre) at the origin.
Eigen::Isometry3d UprightFrameOf(const RegistrationView& view);

}  // namespace simtree::registration
