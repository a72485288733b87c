#pragma once
// Deflection signals of marker links (paper Fig. 8): the markers, linked child to parent into a
// simplified tree, give one link per non-root marker. A link's deflection is the angle of the
// child link (parent marker -> child marker) against its parent link (grandparent marker ->
// parent marker), theta_k(t) of Fig. 8b, split into the two bending planes of the link:
//
//   v  the link's rest direction;
//   u  normal to the plane of the link and its parent link (parent_v x v), the convention of the
//      branch frames (core/frames.h), so bend_u of a branch matches theta_u of its link;
//   w  = u x v, in that plane.
//
// The parent link's rotation (the shortest rotation from its rest direction to its current one)
// is taken out first, so the parent's swing does not show in the child's signal. A link from the
// root marker has no parent link: its angle is against the camera's fixed frame. The root marker
// itself (the trunk) gets a displacement signal: its motion from rest along the two directions it
// moves most (metres).

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "simtree/identification/detail/sampled_signal.h"
#include "simtree/io/capture.h"
#include "simtree/io/trajectories.h"

namespace simtree::identification {

// One link of the simplified tree.
struct DeflectionLink {
  int child = 0;              // marker id
  int parent = -1;            // marker id; -1: the root marker's own displacement
  int grandparent = -1;       // marker id of the parent's parent; -1 when the parent is the root
  std::string label;          // "M0-M1" (parent label - child label), or the root's label
  std::optional<int> branch;  // the child marker's branch in the static tree, when known

  bool is_root() const { return parent < 0; }
};

// One link per marker of markers.json, in its order (the root's displacement first when
// `include_root`).
std::vector<DeflectionLink> LinksFromMarkers(const std::vector<MarkerLink>& markers,
                                             bool include_root = true);

enum class DeflectionKind { kRelativeAngle, kDisplacement };
const char* ToString(DeflectionKind kind);  // "relative_angle", "displacement"

struct DeflectionOptions {
  // The "parent axis" of links from the root marker, in camera coordinates: up, for a camera
  // held level (OpenCV y points down). Only the naming of the two planes depends on it.
  Eigen::Vector3d camera_up = -Eigen::Vector3d::UnitY();
  // The rest pose is the mean over this last share of the frames given (the decay's tail, where
  // the swing is smallest and averages out over whole cycles), in (0, 1].
  double rest_fraction = 0.5;

  // Throws InputError naming the field for a value out of range.
  void Validate() const;
};

// Whether a link has a signal, and why not.
enum class DeflectionStatus {
  kOk,
  kMissingTrajectory,  // a marker of the link is in the marker list but has no trajectory
  kTooFewFrames,       // fewer than 2 frames in the record
  kNoRestPose,         // a marker of the link is never valid at the end of the record
  kCoincidentMarkers,  // the link's two markers coincide at rest: no direction
};
// "ok", "missing_trajectory", "too_few_frames", "no_rest_pose", "coincident_markers".
const char* ToString(DeflectionStatus status);

struct DeflectionSignal {
  DeflectionLink link;
  DeflectionKind kind = DeflectionKind::kRelativeAngle;
  // Two channels: theta_u, theta_w (rad), or d_1, d_2 (m) for a displacement. Empty (zero
  // samples) unless `status` is kOk.
  SampledSignal signal;
  Eigen::Vector3d u = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero(),
                  w = Eigen::Vector3d::Zero();  // rest frame, camera coordinates
  double rest_length_m = 0.0;                   // parent marker to child marker at rest
  DeflectionStatus status = DeflectionStatus::kOk;
  std::string problem;  // why there is no signal, for a person ("marker 7 has no trajectory")

  bool ok() const { return status == DeflectionStatus::kOk; }
};

// The deflection of every link over frames [first_frame, end_frame) of `trajectories`
// (end_frame < 0: to the end). A link whose markers have no track, or no valid rest pose, gets an
// empty signal, a `status` and a `problem`.
std::vector<DeflectionSignal> ComputeDeflectionSignals(const Trajectories& trajectories,
                                                       const std::vector<DeflectionLink>& links,
                                                       int first_frame, int end_frame,
                                                       const DeflectionOptions& options = {});

}  // namespace simtree::identification
