// WriteTrackOutputs: trajectories.csv, boxes.csv, track_summary.json, overlay frames and video.
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/progress.h"
#include "simtree/io/capture.h"
#include "simtree/tracking/boxes_file.h"
#include "simtree/tracking/detail/overlay.h"
#include "simtree/tracking/track.h"

namespace fs = std::filesystem;

namespace simtree::tracking {
namespace {

std::string SummaryJson(const TrackResult& result) {
  nlohmann::ordered_json doc;
  doc["format"] = "simtree.track_summary";
  doc["version"] = 1;
  doc["frames"] = result.trajectories.frame_count();
  doc["color_model"] = result.color_model;
  nlohmann::ordered_json markers = nlohmann::ordered_json::array();
  for (const MarkerCounts& c : result.counts) {
    markers.push_back(
        {{"id", c.marker}, {"tracked", c.tracked}, {"predicted", c.predicted}, {"lost", c.lost}});
  }
  doc["markers"] = markers;
  nlohmann::ordered_json flagged = nlohmann::ordered_json::array();
  for (const FlaggedFrame& f : result.flagged) {
    flagged.push_back({{"frame", f.frame}, {"reason", f.reason}});
  }
  doc["flagged_frames"] = flagged;
  doc["never_found"] = result.never_found;
  doc["warnings"] = result.warnings;
  return doc.dump(1) + "\n";
}

void WriteOverlay(const TrackResult& result, const fs::path& out_dir,
                  const TrackOutputOptions& options) {
  PullStream pull;
  pull.directory = result.pull_dir;
  pull.intrinsics = result.intrinsics;
  pull.frames = ReadFramesCsv(result.pull_dir / "frames.csv");
  if (pull.frames.size() != result.boxes.size()) {
    throw InputError((result.pull_dir / "frames.csv").string(), "",
                     fmt::format("expected the {} frames tracked, found {}", result.boxes.size(),
                                 pull.frames.size()));
  }
  AtomicDirectory dir(out_dir / "overlay");
  Progress progress("overlay", static_cast<int64_t>(result.boxes.size()), "frames");
  for (size_t i = 0; i < result.boxes.size(); ++i) {
    const RgbImage color = ReadColorImage(pull.directory / pull.frames[i].color);
    WritePng(detail::DrawOverlay(color, result, i, options.trail_frames),
             dir.path() / fmt::format("{:06d}.png", i));
    progress.Advance();
  }
  progress.Done();
  if (options.video) {
    double fps = options.video_fps;
    if (fps <= 0.0) fps = pull.FrameRate() > 0.0 ? pull.FrameRate() : 30.0;
    const fs::path staged = out_dir / ".overlay.mp4.partial";
    detail::EncodeVideo(dir.path() / "%06d.png", fps, staged);
    fs::rename(staged, out_dir / "overlay.mp4");
  }
  dir.Commit();
}

}  // namespace

void WriteTrackOutputs(const TrackResult& result, const fs::path& out_dir,
                       const TrackOutputOptions& options) {
  RefuseToOverwriteInputs(out_dir, {result.pull_dir});
  fs::create_directories(out_dir);
  WriteTrajectoriesCsv(result.trajectories, out_dir / "trajectories.csv");
  WriteBoxesCsv(result.boxes, out_dir / "boxes.csv");
  WriteFileAtomically(out_dir / "track_summary.json", SummaryJson(result));
  // identify finds the marker links beside the trajectories.
  const fs::path markers = result.pull_dir / "markers.json";
  if (fs::exists(markers)) WriteFileAtomically(out_dir / "markers.json", ReadFile(markers));
  if (options.overlay || options.video) WriteOverlay(result, out_dir, options);
}

}  // namespace simtree::tracking
