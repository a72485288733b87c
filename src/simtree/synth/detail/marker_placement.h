#pragma once
// Red tape markers for the pull test of a synthetic tree, as in the paper (Fig. 6, 8): markers on
// branches of every level, linked into a simplified tree whose root marker sits on the trunk.
//
// Where a marker may go (a "site"): a node of a branch whose radius is at least min_radius_m (a
// band of tape needs something to wrap around), at least fork_clearance_m (and 3 radii) of arc
// away from the branch's base, its tip and every child's attachment, so the tape sits on a plain
// stretch of branch.
//
// How sites are chosen:
//  1. The root marker: the best trunk site below the lowest branch (so it lies on the path from
//     every other marker to the ground).
//  2. Chains: a few level-1 branches spread around the crown (the first one on
//     `first_chain_branch` when given: the branch the rope pulls), each followed down the hierarchy
//     (a child attached beyond the parent's marker, preferring children whose subtree reaches the
//     deepest taped level), one marker per level, so every level is taped and each link joins a
//     branch to its parent, as the paper's Fig. 8.
//  3. The rest, one per branch, by score, away from markers already placed.
// A site's score prefers (with a camera position) sites the camera sees (most of the band's face
// towards the camera, 9 points over its length and width, clear of every other branch), on the
// camera's side of the crown, on a branch running across the view, and
// (always) in the middle of its branch; seeded jitter breaks ties.
//
// Links: a marker's parent is the nearest marker on its way down to the trunk base (the same
// branch closer to its base, else the parent branch below the attachment, and so on), else the
// root. Ids are ordered parents first; labels are "M<id>"; `position` is the rest position.

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "simtree/core/tree.h"

namespace simtree::synth {

struct MarkerPlacementOptions {
  int count = 12;  // markers to place (fewer if the tree has fewer sites)
  // Thinnest branch to tape: 3 mm (a 6 mm twig), so the slender twig levels of small trees
  // (level 4 ends at 3-5 mm) still get a marker, as in the paper.
  double min_radius_m = 0.003;
  std::optional<Eigen::Vector3d> camera_position = std::nullopt;  // world; none: no preference
  // A level-1 branch the first chain must start on (the pulled one, so the pull excites a taped
  // chain); none, or a branch with no site: the best-scoring one.
  std::optional<int> first_chain_branch = std::nullopt;
  // Sites not to use, as (branch, arc length): no site within 2 fork_clearance_m of one on the
  // same branch (e.g. tapes a renderer found hidden: it sees props and partial occlusion the
  // line-of-sight test below does not).
  std::vector<std::pair<int, double>> excluded_sites = {};
  uint64_t seed = 0;
  double fork_clearance_m = 0.05;
};

struct MarkerPlacementResult {
  std::vector<int> markers_per_level;  // index = branch level
  int sites = 0;                       // candidate sites found
  int hidden = 0;                      // placed markers the camera does not see (0 without one)
};

// Replaces `tree.markers`. Throws InputError when the count is below 1 or the radius not
// positive, or the tree has no site on its trunk.
MarkerPlacementResult PlaceMarkers(Tree& tree, const MarkerPlacementOptions& options = {});

}  // namespace simtree::synth
