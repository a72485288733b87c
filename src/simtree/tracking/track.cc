#include "simtree/tracking/track.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/core/progress.h"
#include "simtree/tracking/detail/color_model.h"
#include "simtree/tracking/detail/frame_loader.h"
#include "simtree/tracking/detail/marker_tracker.h"
#include "simtree/tracking/detail/pull_input.h"
#include "simtree/tracking/detail/trajectory_smoother.h"

namespace simtree::tracking {
namespace {

void RequireRange(double value, double low, double high, const char* field) {
  if (!(value >= low && value <= high)) {
    throw InputError("TrackOptions", field,
                     fmt::format("expected a value in [{}, {}], got {}", low, high, value));
  }
}

// A frame before the init frame: every marker lost, nothing measured.
void AddUnseenFrame(const PullFrame& frame, const std::vector<int>& ids, TrackResult* result) {
  const size_t n = ids.size();
  result->trajectories.AddFrame(
      frame.frame, frame.time_s,
      std::vector<Eigen::Vector3d>(n, Eigen::Vector3d::Constant(std::nan(""))),
      std::vector<bool>(n, false));
  FrameBoxes boxes{frame.frame, {}};
  for (int id : ids) {
    MarkerBox box;
    box.marker = id;
    boxes.markers.push_back(box);
  }
  result->boxes.push_back(std::move(boxes));
}

void AddTrackedFrame(const PullFrame& frame, const std::vector<detail::MarkerFrameResult>& marks,
                     TrackResult* result) {
  std::vector<Eigen::Vector3d> positions;
  std::vector<bool> valid;
  FrameBoxes boxes{frame.frame, {}};
  for (const detail::MarkerFrameResult& m : marks) {
    positions.push_back(m.measured ? m.position : Eigen::Vector3d::Constant(std::nan("")));
    valid.push_back(m.measured);
    boxes.markers.push_back(m.box);
  }
  result->trajectories.AddFrame(frame.frame, frame.time_s, positions, valid);
  result->boxes.push_back(std::move(boxes));
}

// Per-marker counts, markers never measured, and a warning for each.
void Summarise(TrackResult* result) {
  for (size_t i = 0; i < result->trajectories.tracks.size(); ++i) {
    MarkerCounts c;
    c.marker = result->trajectories.tracks[i].marker;
    for (const FrameBoxes& f : result->boxes) {
      const MarkerState s = f.markers[i].state;
      (s == MarkerState::kTracked     ? c.tracked
       : s == MarkerState::kPredicted ? c.predicted
                                      : c.lost)++;
    }
    result->counts.push_back(c);
    if (result->trajectories.tracks[i].valid_count() == 0) {
      result->never_found.push_back(c.marker);
      result->warnings.push_back(
          fmt::format("marker {} was never measured: no tape of the model's colour with depth "
                      "near its init pixel in any frame",
                      c.marker));
    }
  }
}

}  // namespace

const char* ToString(MarkerState state) {
  switch (state) {
    case MarkerState::kTracked:
      return "tracked";
    case MarkerState::kPredicted:
      return "predicted";
    case MarkerState::kLost:
      return "lost";
  }
  return "lost";
}

MarkerState ParseMarkerState(const std::string& text, const std::string& source) {
  for (MarkerState s : {MarkerState::kTracked, MarkerState::kPredicted, MarkerState::kLost}) {
    if (text == ToString(s)) return s;
  }
  throw InputError(source, "state",
                   fmt::format("expected tracked, predicted or lost, got '{}'", text));
}

const char* ToString(MotionModelKind kind) {
  return kind == MotionModelKind::kDampedOscillator ? "damped_oscillator" : "constant_velocity";
}

void TrackOptions::Validate() const {
  detail::ColorModelFromName(color);
  RequireRange(search_radius_px, 2.0, 500.0, "search_radius_px");
  RequireRange(reacquire_radius_px, search_radius_px, 1000.0, "reacquire_radius_px");
  RequireRange(gate_mm, 1.0, 2000.0, "gate_mm");
  RequireRange(gate_px, 1.0, 500.0, "gate_px");
  RequireRange(max_coast_frames, 0, 1000, "max_coast_frames");
  RequireRange(min_blob_pixels, 1, 1000, "min_blob_pixels");
  RequireRange(split_depth_mm, 1.0, 10000.0, "split_depth_mm");
  RequireRange(process_noise_mps2, 1e-3, 1e3, "process_noise_mps2");
  RequireRange(measurement_noise_mm, 1e-3, 1e3, "measurement_noise_mm");
  RequireRange(measurement_depth_noise_mm, 1e-3, 1e3, "measurement_depth_noise_mm");
  RequireRange(threads, 0, 1024, "threads");
}

TrackResult Track(const std::filesystem::path& pull_dir, const TrackInit& init,
                  const TrackOptions& options) {
  options.Validate();
  const PullStream stream = detail::OpenPullStream(pull_dir);
  const size_t start = detail::CheckInit(stream, init, "init");
  detail::FrameLoader loader(stream, options.threads);
  const detail::TapeColorModel model =
      detail::ChooseColorModel(options.color, loader.Get(start).color, init,
                               (stream.directory / stream.frames[start].color).string());

  std::vector<int> ids;
  std::vector<Eigen::Vector2d> pixels;
  for (const MarkerPixel& m : init.markers) {
    ids.push_back(m.id);
    pixels.push_back(m.pixel);
  }
  TrackResult result;
  result.intrinsics = stream.intrinsics;
  result.pull_dir = pull_dir;
  result.color_model = model.Describe();
  for (int id : ids) {
    MarkerTrack track;
    track.marker = id;
    result.trajectories.tracks.push_back(std::move(track));
  }
  detail::MarkerTracker tracker(options, model, stream.intrinsics, ids, pixels);

  Progress progress("track", static_cast<int64_t>(stream.frames.size()), "frames");
  for (size_t i = 0; i < stream.frames.size(); ++i) {
    const PullFrame& frame = stream.frames[i];
    if (i < start) {
      AddUnseenFrame(frame, ids, &result);
    } else {
      const double dt = i > start ? frame.time_s - stream.frames[i - 1].time_s : 0.0;
      const auto marks = tracker.Step(loader.Get(i), dt);
      AddTrackedFrame(frame, marks, &result);
      if (!tracker.last_frame_had_color()) {
        result.flagged.push_back({frame.frame, "no pixel of the tape colour in the frame"});
      } else if (std::none_of(marks.begin(), marks.end(),
                              [](const auto& m) { return m.box.state == MarkerState::kTracked; })) {
        result.flagged.push_back({frame.frame, "no marker found"});
      }
    }
    progress.Advance();
  }
  progress.Done();
  if (options.smooth) {
    detail::SmoothTrajectories(
        result.trajectories,
        detail::SmootherOptions{.process_noise_mps2 = options.process_noise_mps2,
                                .noise_xy_m = options.measurement_noise_mm / 1000.0,
                                .noise_z_m = options.measurement_depth_noise_mm / 1000.0});
  }
  Summarise(&result);
  return result;
}

}  // namespace simtree::tracking
