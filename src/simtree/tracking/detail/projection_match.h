#pragma once
// Which tape blob of a frame is which marker, given where a known camera pose projects each
// marker: a registration error of a degree or two moves every projection by about the same
// image offset (f tan(angle), 15 px at f = 434), far more than the spacing of neighbouring
// tapes allows to take each projection's nearest blob. So: find the common correction first (the
// offset most projections agree on, by voting over projection-blob pairs within each marker's
// pose gate, then a similarity transform fitted to the agreeing pairs), and only then assign
// blobs to corrected projections (Hungarian on pixel distance with a tight gate).

#include <vector>

#include <Eigen/Core>

namespace simtree::tracking::detail {

struct ProjectionMatchOptions {
  // A blob agrees with a corrected projection within this (px): what remains after the common
  // correction (the tape's centre against its axis point, parallax of the translation error).
  double match_radius_px = 6.0;
  // The final gate follows how well the correction fits: `residual_factor` times the median
  // distance of the first assignment's pairs, within [min_match_radius_px, match_radius_px]. A
  // good fit leaves a marker whose own tape is not seen no room to take a neighbour's fragment.
  double min_match_radius_px = 3.5;
  double residual_factor = 3.0;
  // A similarity (rotation, scale, shift) is fitted from this many agreeing pairs on; fewer keep
  // the shift alone.
  int min_pairs_for_similarity = 3;
  // A fitted similarity that rotates or scales more than this is not a pose error: keep the shift.
  double max_rotation_deg = 6.0;
  double max_scale_change = 0.08;
};

struct ProjectionMatch {
  std::vector<int> blob;  // per projection: the blob matched to it, -1 for none in the gate
  std::vector<double> distance_px;         // per projection: to its blob after the correction (-1)
  std::vector<Eigen::Vector2d> corrected;  // per projection, after the correction
  Eigen::Vector2d shift_px = Eigen::Vector2d::Zero();  // the common correction's shift ...
  double rotation_deg = 0.0;                           // ... rotation about the projections'
  double scale = 1.0;                                  // centroid and scale
  int agreeing = 0;                                    // projections that voted for the correction
  double gate_px = 0.0;                                // the final gate (px)
};

// `projections` with their gates (px: how far the pose's uncertainty may move each one),
// `blobs` the detected tape centres. Every input projection gets an entry; a projection with no
// blob within the final gate of its corrected position is left unmatched, never given a far one.
ProjectionMatch MatchProjections(const std::vector<Eigen::Vector2d>& projections,
                                 const std::vector<double>& gates_px,
                                 const std::vector<Eigen::Vector2d>& blobs,
                                 const ProjectionMatchOptions& options);

}  // namespace simtree::tracking::detail
