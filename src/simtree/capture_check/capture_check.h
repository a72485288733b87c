#pragma once
// `simtree capture-check`: what a user should fix in a capture before the long run. Each check
// has a value, thresholds derived from what the stages need (docs/capturing.md says why) and an
// outcome with a one-line fix:
//   scan views      count, and per view: depth on the tree, distance, blur, exposure
//   view coverage   the largest angle around the tree without a view (a quick registration)
//   pull stream     frames, rate, length, dropped frames, and in its first frame: depth on the
//                   tree, distance, tape markers found and their width in pixels, blur,
//                   exposure
// "The tree" in a frame is what preprocessing keeps of it (ground and outliers removed, the
// largest cluster), projected back into the image.
//
// Usage:
//   namespace cc = simtree::capture_check;
//   const cc::CaptureCheckResult result = cc::CheckCapture("capture/", {});
//   std::puts(cc::FormatTable(result).c_str());
//   return result.Worst() == cc::Status::kFail ? 1 : 0;

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "simtree/io/capture_from_recordings.h"

namespace simtree::capture_check {

inline constexpr const char* kCaptureCheckFormat = "simtree.capture_check";
inline constexpr int kCaptureCheckFormatVersion = 1;

enum class Status { kOk, kWarn, kFail, kSkipped };
const char* ToString(Status status);  // "ok", "warn", "fail", "skipped"

// The limits of each check: "warn" where the stage starts to lose accuracy, "fail" where it
// cannot work. Defaults and their reasons: docs/capturing.md, "What capture-check checks".
struct CheckThresholds {
  int warn_views = 4;                   // fewer scan views: warn
  double warn_frame_rate_hz = 25;       // below: warn
  double fail_frame_rate_hz = 15;       // below: fail
  double warn_duration_s = 10;          // a shorter pull record: warn
  double fail_dropped_share = 0.05;     // more frames dropped: fail (any dropped: warn)
  double warn_tree_depth_share = 0.75;  // less of the tree with depth: warn
  double fail_tree_depth_share = 0.5;   // fail
  double min_distance_m = 0.5;          // the depth camera's near limit: fail
  double warn_distance_m = 3.5;         // farther: warn
  double max_distance_m = 3.86;         // the far limit (NFOV unbinned): fail
  // The tapes' width (the narrower side of the tracker's band model, px): median below warn, or
  // any tape below fail: warn; median below fail: fail.
  double warn_tape_px = 3;
  double fail_tape_px = 1.5;
  // The blur effect on the tree (0 sharp, 1 blurred; detail/frame_quality.h): warn. Synth's
  // frames read 0.44-0.50 sharp, the real Azure Kinect frame 0.60; above 0.7 thin tapes (3 px)
  // lose half their samples or more (docs/capturing.md).
  double warn_blur = 0.7;
  double warn_clipped_share = 0.05;    // over- or under-exposed share of the tree: warn
  double fail_clipped_share = 0.25;    // fail
  double warn_coverage_gap_deg = 120;  // a larger angle around the tree without a view: warn
  void Validate() const;
};

struct CaptureCheckOptions {
  CheckThresholds thresholds;
  std::string tape_color = "auto";  // the tracker's --color
  bool register_views = true;       // view coverage by a quick registration (else skipped)
  void Validate() const;
};

struct Check {
  std::string name;     // "tape width"
  std::string subject;  // "view_02", "pull frame 0", "scans", "pull"
  double value = 0;     // NaN when there is none
  std::string unit;     // "px", "m", "%", "fps", ...
  std::string limits;   // "warn < 4, fail < 3"
  Status status = Status::kOk;
  std::string message;  // what was found and, unless ok, the fix
};

struct CaptureCheckResult {
  std::filesystem::path capture;
  std::vector<Check> checks;
  double seconds = 0;
  Status Worst() const;  // fail over warn over ok; skipped counts as ok
  int Count(Status status) const;
};

// Checks a capture folder (docs/formats.md). Throws InputError when `capture` is missing, is not
// a capture folder or one of its small files is broken; a bad image or view is a failed check.
CaptureCheckResult CheckCapture(const std::filesystem::path& capture,
                                const CaptureCheckOptions& options = {});

// Recordings in any layout `capture-from` reads (Azure .mkv, RealSense .bag, TUM, Open3D),
// converted into a temporary capture folder and checked there, plus "recording drops": pull
// captures the conversion left out (the camera's dropped frames, captures lacking colour or
// depth). Throws InputError as CaptureFromRecordings does.
CaptureCheckResult CheckRecordings(const CaptureFromOptions& recordings,
                                   const CaptureCheckOptions& options = {});

// A table for people, one check a line, with the fixes after it.
std::string FormatTable(const CaptureCheckResult& result);
// `simtree.capture_check` v1 (docs/formats.md).
nlohmann::ordered_json ToJson(const CaptureCheckResult& result);

}  // namespace simtree::capture_check
