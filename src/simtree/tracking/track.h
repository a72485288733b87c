#pragma once
// `simtree track`: follows every tape marker of a pull-test stream (a capture's pull/ folder)
// through its colour and depth frames and gives each marker's 3D centre per frame (paper III-C).
//
// Per frame: predict every marker with its own 3D motion model, look for tape-coloured blobs
// near each prediction (a colour model fitted to the first frame's marker pixels), split blobs
// where markers cross (by depth), measure each blob's sub-pixel centre, its 3D centre (a robust
// low quantile of its own depth pixels, pushed from the tape's front to the branch axis) and the
// box of the whole tape band, assign blobs to predictions (gated Hungarian on image distance and
// depth difference), and keep a state per marker: tracked (measured this frame), predicted
// (coasting through a short loss) or lost. A marker found again after a loss is re-identified by
// its predicted position and its rest position. After the last frame each run of measured positions
// is smoothed (Kalman forward, Rauch-Tung-Striebel backward). Trajectories hold measured positions
// only: valid 0 wherever a marker was not measured.
//
//   const TrackInit init = ReadTrackInitJson(capture / "pull" / "init.json");
//   TrackResult result = Track(capture / "pull", init, TrackOptions{});
//   WriteTrackOutputs(result, "tracks/", TrackOutputOptions{.overlay = true});

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "simtree/io/capture.h"
#include "simtree/io/track_init.h"
#include "simtree/io/trajectories.h"

namespace simtree::tracking {

// How a marker stands in one frame.
enum class MarkerState {
  kTracked,    // measured in this frame (trajectories.csv valid = 1)
  kPredicted,  // not measured; its box is the motion model's prediction (valid = 0)
  kLost,       // not measured for longer than the coasting limit (valid = 0)
};
const char* ToString(MarkerState state);
// "tracked", "predicted" or "lost"; throws InputError naming `source` otherwise.
MarkerState ParseMarkerState(const std::string& text, const std::string& source);

enum class MotionModelKind {
  kConstantVelocity,  // constant velocity Kalman filter per axis
  kDampedOscillator,  // a damped oscillator about the marker's rest position per axis
};
const char* ToString(MotionModelKind kind);

// The focal length (px) the tracker's pixel options are given for: synth's 640 x 576 depth camera
// (75 degrees wide, 320 / tan 37.5 deg). A marker's size and motion in pixels grow with the focal
// length, not the image width, so the options scale with fx / kReferenceFocalPx.
inline constexpr double kReferenceFocalPx = 434.19751177064387;

struct TrackOptions {
  // The tape colour: "auto" (red, its hue and saturation fitted to the init pixels), "red",
  // "green", "blue", "yellow", "orange" or "#rrggbb" (a hue fitted around that colour).
  std::string color = "auto";
  // Half-size of the square searched around a marker's prediction (px for a focal length of
  // 434 px, synth's 640 x 576 depth camera; scaled with the stream's focal length, fx / 434).
  double search_radius_px = 18.0;
  // Half-size searched around a lost marker's last and rest positions (px, same scaling).
  double reacquire_radius_px = 40.0;
  // Largest depth difference between a prediction and a detection assigned to it (mm; grown by
  // three standard deviations of the prediction; three times this for a marker found again).
  double gate_mm = 60.0;
  // Largest image distance between a prediction and a detection assigned to it (px, scaled).
  double gate_px = 14.0;
  // Frames a marker coasts on its prediction before it is called lost.
  int max_coast_frames = 10;
  // Fewest tape pixels a blob needs to count as a detection.
  int min_blob_pixels = 3;
  // Depth step that splits one blob into two markers crossing in the image (mm).
  double split_depth_mm = 40.0;
  // Motion model of every marker.
  MotionModelKind motion_model = MotionModelKind::kConstantVelocity;
  // Acceleration noise of the motion model (m/s^2, white).
  double process_noise_mps2 = 8.0;
  // Standard deviation of a measured 3D centre across / along the viewing ray (mm).
  double measurement_noise_mm = 2.0;
  double measurement_depth_noise_mm = 8.0;
  // Smooth the measured positions afterwards (forward Kalman and backward Rauch-Tung-Striebel
  // passes over each run of measured frames; gaps stay gaps).
  bool smooth = true;
  // Threads loading frames (0: all cores). Tracking itself is sequential (frame after frame).
  int threads = 0;
  // Throws InputError naming the field when an option is out of range.
  void Validate() const;
};

// One marker in one frame: the box of its whole tape band (x, y of the top-left corner, width,
// height; pixel centres at integer coordinates, so a one-pixel box at pixel (u, v) is
// [u - 0.5, v - 0.5, 1, 1]), its centre, its state and a confidence in [0, 1] (0 when lost).
struct MarkerBox {
  int marker = 0;
  std::array<double, 4> box = {0, 0, 0, 0};
  std::array<double, 2> center = {0, 0};
  MarkerState state = MarkerState::kLost;
  double confidence = 0.0;
};

struct FrameBoxes {
  int frame = 0;
  std::vector<MarkerBox> markers;  // in the order of TrackResult::trajectories.tracks
};

// Per marker: how many frames it spent in each state.
struct MarkerCounts {
  int marker = 0;
  int tracked = 0;
  int predicted = 0;
  int lost = 0;
};

// A frame the tracker could not use as it should: no tape colour anywhere, or every marker lost.
struct FlaggedFrame {
  int frame = 0;
  std::string reason;
};

struct TrackResult {
  Trajectories trajectories;         // pull camera frame, metres; valid only where measured
  std::vector<FrameBoxes> boxes;     // one per frame
  std::vector<MarkerCounts> counts;  // one per marker, in trajectories order
  std::vector<FlaggedFrame> flagged;
  CameraIntrinsics intrinsics;
  std::filesystem::path pull_dir;
  std::string color_model;  // the tape colour model used, in words
  // Markers of the init that were never measured (each also a warning in `warnings`).
  std::vector<int> never_found;
  std::vector<std::string> warnings;
};

// Tracks the markers of `init` through the stream in `pull_dir` (intrinsics.json, frames.csv,
// markers.json when present, color/, depth/). Frames before init.frame are reported lost. Throws
// InputError for options out of range, an init naming a marker markers.json lacks or a frame not
// in frames.csv, a missing or unreadable frame, depth of the wrong size, or an init whose pixels
// show no tape of the chosen colour at all. Shows progress on long streams.
TrackResult Track(const std::filesystem::path& pull_dir, const TrackInit& init,
                  const TrackOptions& options);

struct TrackOutputOptions {
  // Overlay PNG frames (overlay/NNNNNN.png: boxes, ids, trails) from the stream's colour frames.
  bool overlay = false;
  // overlay.mp4 (H.264 through the ffmpeg binary; implies the overlay frames).
  bool video = false;
  // Frames per second of the video (0: the stream's own rate).
  double video_fps = 0.0;
  // Length of the trails drawn behind each marker (frames).
  int trail_frames = 20;
};

// Writes trajectories.csv, boxes.csv, track_summary.json and a copy of the stream's markers.json
// (what `identify` reads beside the trajectories) into `out_dir` (created when absent), and the
// overlay frames and video when asked. Every file appears whole or not at all. Throws
// IoError when ffmpeg is asked for and not installed.
void WriteTrackOutputs(const TrackResult& result, const std::filesystem::path& out_dir,
                       const TrackOutputOptions& options = {});

}  // namespace simtree::tracking
