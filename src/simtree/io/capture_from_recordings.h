#pragma once
// A capture folder (docs/formats.md, "Capture folder") from recordings: each scan recording
// becomes scans/view_XX/ (its sharpest still capture), the pull recording becomes pull/ (every
// capture, frames.csv with the recording's timestamps). markers.json and init.json stay the
// user's. A recording is an Azure Kinect .mkv (colour undistorted to a pinhole camera and depth
// registered into it), a TUM RGB-D folder or an Open3D folder (io/recording_layout.h; their
// colour and depth are registered already), each input's layout detected from its path.
//
//   CaptureFromOptions options;
//   options.scans = {"north.mkv", "east.mkv"};
//   options.pull = "pull.mkv";
//   AtomicDirectory out("capture/");
//   const CaptureFromResult result = CaptureFromRecordings(options, out.path());
//   out.Commit();

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "simtree/io/azure_kinect.h"
#include "simtree/io/image_io.h"
#include "simtree/io/recording_layout.h"

namespace simtree {

struct CaptureFromOptions {
  std::vector<std::filesystem::path> scans;   // one recording per view, in view order
  std::optional<std::filesystem::path> pull;  // the pull test's recording
  // A scan view is the sharpest of the recording's still captures: those whose motion (mean
  // absolute grey change to their neighbours, 0-255) is at most the larger of this and the
  // recording's 25th percentile of motion.
  double still_motion_grey = 1.0;
  int max_pull_frames = 0;  // 0: every capture
  // Put each pull frame at frame number x the stream's mean period instead of its recorded time.
  // For recordings with millisecond timestamps (those libav writes, e.g. capture-export's): their
  // 33/34 ms steps are no regular grid, which identify requires. k4arecorder's are microseconds.
  bool snap_pull_times = false;
  // Also write check/<view>.png and check/pull_first.png: colour with depth blended in and with
  // depth edges drawn, to see by eye that depth sits on the colour (io/detail/
  // registration_overlay.h). Not part of the capture.
  bool write_check_images = false;
  // Every input's layout; kAuto detects each one's from its path.
  RecordingLayout layout = RecordingLayout::kAuto;
  AzureReaderOptions reader;
  AzureRegistrationOptions registration;
  RgbdSequenceOptions sequence;  // TUM and Open3D inputs
  PngOptions png;
  void Validate() const;
};

// How one scan view was chosen.
struct ScanViewPick {
  std::string view;  // "view_00"
  std::filesystem::path recording;
  int capture = 0;     // index of the chosen capture in the recording
  int candidates = 0;  // captures with colour and depth
  int still = 0;       // of them, those counted as still
  int64_t timestamp_us = 0;
  double sharpness = 0;  // variance of the grey Laplacian of the chosen capture
  double motion_grey = 0;
};

struct CaptureFromResult {
  std::vector<ScanViewPick> views;
  int pull_frames = 0;
  int pull_skipped = 0;  // pull captures without colour or depth (the camera dropped one)
  double pull_duration_s = 0;
  double pull_time_snap_max_s = 0;  // the largest move snap_pull_times made
  AzureReadStats pull_stats;  // of the pull recording (.mkv; of another layout: captures and rate)
  RecordingLayout pull_layout = RecordingLayout::kAuto;  // the pull recording's, when there is one
  std::string sensor;  // capture.json's sensor: "azure_kinect_nfov_unbinned", "tum_rgbd", ...
};

// Writes capture.json, scans/ and pull/ into `capture_root` (a staging folder: the caller
// commits it). Throws InputError naming the recording and frame on bad input.
CaptureFromResult CaptureFromRecordings(const CaptureFromOptions& options,
                                        const std::filesystem::path& capture_root);

}  // namespace simtree
