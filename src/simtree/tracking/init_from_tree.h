#pragma once
// The tracker's start without a person clicking: a static tree that carries its markers (each a
// 3D rest position; synth's gt/tree.json, a simulation-ready tree of an earlier run, a tree
// annotated by hand) and the pull camera's pose in that tree's frame (register's
// pull_camera.json) say where every marker should appear in the pull stream's first frame.
// Each marker's 3D point is projected there and matched to the tape blobs found in the frame
// (detail/projection_match.h: the pose's common error corrected first, then a Hungarian
// assignment on pixel distance with a tight gate). The init's pixel is the matched blob's
// measured centre. A marker outside the image, behind the camera, or with no blob in its gate is
// reported and left out of the init, never placed on a guess.
//
//   const Tree tree = ReadTreeJson("gt/tree.json");
//   const Eigen::Isometry3d pose = ReadCameraPoseJson("gt/pull_camera.json");
//   const InitFromTreeResult r = InitFromTree("capture/pull", tree, pose, {});
//   WriteTrackInitJson(r.init, "init.json");  // r.markers says what became of each marker

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "simtree/core/tree.h"
#include "simtree/io/track_init.h"

namespace simtree::tracking {

struct InitFromTreeOptions {
  // The tape colour, as TrackOptions::color ("auto": red, refitted to the tape near the
  // projections).
  std::string color = "auto";
  // How wrong the pose may be: registration places the pull camera within a degree or two and a
  // few centimetres. A marker's blob is searched within f tan(rotation) + f translation / depth
  // (+ the match radius) of its projection.
  double pose_rotation_deg = 2.0;
  double pose_translation_m = 0.05;
  // What may remain after the common correction (px at a focal length of 434 px, scaled with the
  // stream's fx as TrackOptions' radii are): the tape's centre against its axis point. The final
  // gate is 3 times the median remainder of the first assignment, within [min, max].
  double match_radius_px = 6.0;
  double min_match_radius_px = 3.5;
  // A marker with no blob in its gate but a corrected projection inside the frame starts there
  // (status kProjected: the tracker looks for it from that pixel, and starts it lost) instead of
  // being left out, and so never tracked. Off: only markers seen on a tape are in the init.
  bool keep_unmatched = false;
  // Fewest tape pixels a blob needs.
  int min_blob_pixels = 3;
  // Throws OptionError naming the field.
  void Validate() const;
};

// What became of one marker of the tree.
enum class MarkerInitStatus {
  kMatched,       // in the init, at its blob's centre
  kNotInMarkers,  // the tree has it, markers.json does not: not tracked
  kBehindCamera,  // its point is behind (or within 5 cm of) the camera
  kOutsideImage,  // it projects outside the frame
  kNoBlob,        // no tape blob within the gate of its corrected projection
  kProjected,     // kNoBlob, but in the init at its corrected projection (keep_unmatched)
};
const char* ToString(MarkerInitStatus status);

struct MarkerInit {
  int id = 0;
  MarkerInitStatus status = MarkerInitStatus::kNoBlob;
  Eigen::Vector2d projected = Eigen::Vector2d::Zero();  // px, with the pose as given
  Eigen::Vector2d corrected = Eigen::Vector2d::Zero();  // px, after the common correction
  // In the init: the matched blob's centre (kMatched) or the corrected projection (kProjected).
  std::optional<Eigen::Vector2d> pixel;
  double distance_px = -1.0;  // from the corrected projection to the blob (-1: none)
  double depth_m = 0.0;       // of the marker's point in the camera frame
};

struct InitFromTreeResult {
  TrackInit init;  // the matched (and kProjected) markers, at the stream's first frame
  std::vector<MarkerInit> markers;  // every marker of the tree, in the tree's order
  std::vector<int> missing;         // markers.json ids the tree has no marker for
  int blobs = 0;                    // tape blobs found in the frame
  double gate_px = 0.0;             // the largest pose gate used (px)
  double match_radius_px = 0.0;     // the final gate, scaled to the stream (px)
  // The common correction of the projections (a pose error seen in the image).
  Eigen::Vector2d shift_px = Eigen::Vector2d::Zero();
  double rotation_deg = 0.0;
  double scale = 1.0;
  std::string color_model;  // in words
  std::vector<std::string> warnings;
};

// Throws InputError for options out of range, a tree without markers (naming `tree_source`), a
// pull folder that does not open, or an init with no marker matched at all (naming what to
// check: the pose, --color).
InitFromTreeResult InitFromTree(const std::filesystem::path& pull_dir, const Tree& tree,
                                const Eigen::Isometry3d& tree_from_camera,
                                const InitFromTreeOptions& options,
                                const std::string& tree_source = "static tree");

}  // namespace simtree::tracking
