#include "simtree/capture_check/capture_check.h"

#include <algorithm>
#include <chrono>

#include "simtree/capture_check/detail/steps.h"
#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/io/capture.h"
#include "simtree/tracking/find_tapes.h"

namespace fs = std::filesystem;

namespace simtree::capture_check {

const char* ToString(Status status) {
  switch (status) {
    case Status::kOk:
      return "ok";
    case Status::kWarn:
      return "warn";
    case Status::kFail:
      return "fail";
    case Status::kSkipped:
      return "skipped";
  }
  return "?";
}

void CheckThresholds::Validate() const {
  CheckAtLeast("warn_views", warn_views, 1);
  CheckOrdered("fail_frame_rate_hz", fail_frame_rate_hz, "warn_frame_rate_hz", warn_frame_rate_hz);
  CheckNonNegative("fail_frame_rate_hz", fail_frame_rate_hz);
  CheckNonNegative("warn_duration_s", warn_duration_s);
  CheckShare("fail_dropped_share", fail_dropped_share);
  CheckShare("fail_tree_depth_share", fail_tree_depth_share);
  CheckShare("warn_tree_depth_share", warn_tree_depth_share);
  CheckOrdered("fail_tree_depth_share", fail_tree_depth_share, "warn_tree_depth_share",
               warn_tree_depth_share);
  CheckNonNegative("min_distance_m", min_distance_m);
  CheckOrdered("min_distance_m", min_distance_m, "warn_distance_m", warn_distance_m);
  CheckOrdered("warn_distance_m", warn_distance_m, "max_distance_m", max_distance_m);
  CheckNonNegative("fail_tape_px", fail_tape_px);
  CheckOrdered("fail_tape_px", fail_tape_px, "warn_tape_px", warn_tape_px);
  CheckShare("warn_blur", warn_blur);
  CheckShare("warn_clipped_share", warn_clipped_share);
  CheckShare("fail_clipped_share", fail_clipped_share);
  CheckOrdered("warn_clipped_share", warn_clipped_share, "fail_clipped_share", fail_clipped_share);
  CheckInRange("warn_coverage_gap_deg", warn_coverage_gap_deg, 0, 360);
}

void CaptureCheckOptions::Validate() const {
  CheckNested("thresholds", thresholds);
  // The tracker's own check of the name: refused before any work.
  tracking::FindTapesOptions tapes;
  tapes.color = tape_color;
  tapes.Validate();
}

Status CaptureCheckResult::Worst() const {
  Status worst = Status::kOk;
  for (const Check& c : checks) {
    if (c.status == Status::kFail) return Status::kFail;
    if (c.status == Status::kWarn) worst = Status::kWarn;
  }
  return worst;
}

int CaptureCheckResult::Count(Status status) const {
  return static_cast<int>(std::count_if(checks.begin(), checks.end(),
                                        [&](const Check& c) { return c.status == status; }));
}

namespace {

// A clear error for what is no capture folder, before OpenCapture's file-by-file ones.
void RequireCaptureFolder(const fs::path& root) {
  if (!fs::exists(root)) throw InputError(root.string(), "", "no such folder");
  if (!fs::is_directory(root)) {
    throw InputError(root.string(), "",
                     "not a folder: give a capture folder (recordings: convert them with "
                     "`simtree capture-from` first)");
  }
  if (!fs::exists(root / "capture.json") && !fs::exists(root / "scans") &&
      !fs::exists(root / "pull")) {
    throw InputError(root.string(), "",
                     "not a capture folder: no capture.json, scans/ or pull/ in it "
                     "(docs/formats.md, \"Capture folder\"), nor a recording capture-from reads "
                     "(an Azure .mkv, a RealSense .bag, a TUM or an Open3D folder)");
  }
}

}  // namespace

CaptureCheckResult CheckCapture(const fs::path& capture_root, const CaptureCheckOptions& options) {
  options.Validate();
  const auto start = std::chrono::steady_clock::now();
  RequireCaptureFolder(capture_root);
  const Capture capture = OpenCapture(capture_root);
  CaptureCheckResult result;
  result.capture = capture_root;
  detail::CheckScans(capture, options, &result.checks);
  detail::CheckPull(capture, options, &result.checks);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace simtree::capture_check
