// CaptureFromRecordings: two passes over each scan recording (score every capture, then fetch the
// chosen one), one pass over the pull recording.

#include "simtree/io/capture_from_recordings.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/progress.h"
#include "simtree/io/detail/registration_overlay.h"
#include "simtree/io/detail/still_frame.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;
using azure_detail::SmallGrey;

bool Complete(const AzureCapture& c) { return c.color.has_value() && c.depth.has_value(); }

std::string SensorName(const AzureKinectReader& reader) {
  const AzureTrack* depth = reader.FindTrack("DEPTH");
  std::string mode = depth && !depth->mode.empty() ? depth->mode : "unknown_mode";
  std::transform(mode.begin(), mode.end(), mode.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return "azure_kinect_" + mode;
}

// The sharpest still frame of a recording's scored frames (`motion_to_previous` -1 where not
// measured): a frame's motion is the larger change to its measured neighbours (0 when it has
// none). Fills everything but the frame's capture index and time; `best` is its position.
ScanViewPick PickStillFrame(const fs::path& recording, const std::vector<double>& sharpness,
                            const std::vector<double>& motion_to_previous,
                            const CaptureFromOptions& options, int* best) {
  const size_t n = sharpness.size();
  std::vector<double> motion(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    motion[i] = std::max(0.0, motion_to_previous[i]);
    if (i + 1 < n) motion[i] = std::max(motion[i], motion_to_previous[i + 1]);
  }
  ScanViewPick pick;
  pick.recording = recording;
  pick.candidates = static_cast<int>(n);
  *best = azure_detail::PickStill(sharpness, motion, options.still_motion_grey, &pick.still);
  pick.sharpness = sharpness[*best];
  pick.motion_grey = motion[*best];
  return pick;
}

// Pass 1: sharpness and motion of every complete capture; the chosen one's index.
ScanViewPick ScoreScan(const fs::path& recording, const CaptureFromOptions& options) {
  AzureKinectReader reader(recording, options.reader);
  std::vector<int> indices;
  std::vector<int64_t> times;
  std::vector<double> sharpness, motion_to_previous;
  std::optional<SmallGrey> previous;
  Progress progress("score " + recording.filename().string(), 0, "captures");
  while (std::optional<AzureCapture> c = reader.Next()) {
    progress.Advance();
    if (!Complete(*c)) {
      previous.reset();  // a gap: the next capture's motion is not measured across it
      continue;
    }
    SmallGrey grey = azure_detail::Shrink(*c->color);
    motion_to_previous.push_back(previous ? azure_detail::Motion(*previous, grey) : -1.0);
    previous = std::move(grey);
    indices.push_back(c->index);
    times.push_back(c->timestamp_us);
    sharpness.push_back(azure_detail::Sharpness(*c->color));
  }
  progress.Done();
  if (indices.empty()) {
    throw InputError(recording.string(), "",
                     "expected at least one capture with both colour and depth, found none");
  }
  int best = 0;
  ScanViewPick pick = PickStillFrame(recording, sharpness, motion_to_previous, options, &best);
  pick.capture = indices[best];
  pick.timestamp_us = times[best];
  return pick;
}

void WriteCheckImage(const RgbdImage& rgbd, const fs::path& capture_root, const std::string& name) {
  fs::create_directories(capture_root / "check");
  WritePng(azure_detail::RegistrationOverlay(rgbd.color, rgbd.depth),
           capture_root / "check" / (name + ".png"));
}

// Pass 2: the chosen capture, registered, written as scans/<view>/.
void WriteScan(const ScanViewPick& pick, const CaptureFromOptions& options,
               const fs::path& capture_root) {
  AzureKinectReader reader(pick.recording, options.reader);
  while (std::optional<AzureCapture> c = reader.Next()) {
    if (c->index != pick.capture) continue;
    const AzureRegistration registration(reader.calibration(), options.registration);
    const RgbdImage rgbd = registration.Apply(*c->color, *c->depth);
    WriteScanView(capture_root, pick.view, rgbd, options.png);
    if (options.write_check_images) WriteCheckImage(rgbd, capture_root, pick.view);
    return;
  }
  throw InputError(pick.recording.string(), fmt::format("capture {}", pick.capture),
                   "expected it on the second pass; the file changed while being read?");
}

// Frame numbers follow the timestamps, so a capture the camera dropped is a skipped number
// (docs/formats.md); the period is the shortest interval seen so far.
class FrameNumbering {
 public:
  int Next(int64_t timestamp_us) {
    if (last_us_ >= 0) {
      const int64_t dt = timestamp_us - last_us_;
      period_us_ = period_us_ > 0 ? std::min(period_us_, dt) : dt;
      frame_ += std::max<int64_t>(1, std::llround(static_cast<double>(dt) / period_us_));
    }
    last_us_ = timestamp_us;
    return static_cast<int>(frame_);
  }

 private:
  int64_t last_us_ = -1;
  int64_t period_us_ = 0;
  int64_t frame_ = 0;
};

// Frame k at k x the mean period (frame numbers count dropped captures); the largest move.
double SnapTimes(std::vector<PullFrame>& frames) {
  const int steps = frames.back().frame - frames.front().frame;
  if (steps <= 0) return 0.0;
  const double period = (frames.back().time_s - frames.front().time_s) / steps;
  double moved = 0;
  for (PullFrame& f : frames) {
    const double snapped = (f.frame - frames.front().frame) * period;
    moved = std::max(moved, std::abs(snapped - f.time_s));
    f.time_s = snapped;
  }
  return moved;
}

void WritePull(const fs::path& recording, const CaptureFromOptions& options,
               const fs::path& capture_root, CaptureFromResult& result) {
  AzureKinectReader reader(recording, options.reader);
  const AzureRegistration registration(reader.calibration(), options.registration);
  const fs::path pull = capture_root / "pull";
  fs::create_directories(pull);
  WriteIntrinsicsJson(registration.color_pinhole(), pull / "intrinsics.json");
  std::vector<PullFrame> frames;
  FrameNumbering numbering;
  int64_t first_us = -1;
  Progress progress("pull " + recording.filename().string(), 0, "frames");
  while (std::optional<AzureCapture> c = reader.Next()) {
    if (options.max_pull_frames > 0 && static_cast<int>(frames.size()) >= options.max_pull_frames)
      break;
    if (!Complete(*c)) {
      ++result.pull_skipped;
      continue;
    }
    if (first_us < 0) first_us = c->timestamp_us;
    const RgbdImage rgbd = registration.Apply(*c->color, *c->depth);
    if (frames.empty() && options.write_check_images) {
      WriteCheckImage(rgbd, capture_root, "pull_first");
    }
    const double time_s = static_cast<double>(c->timestamp_us - first_us) * 1e-6;
    frames.push_back(WritePullFrame(pull, numbering.Next(c->timestamp_us), time_s, rgbd.color,
                                    rgbd.depth, options.png));
    progress.Advance();
  }
  progress.Done();
  if (frames.empty()) {
    throw InputError(recording.string(), "",
                     "expected pull-test captures with both colour and depth, found none");
  }
  if (options.snap_pull_times) result.pull_time_snap_max_s = SnapTimes(frames);
  WriteFramesCsv(frames, pull / "frames.csv");
  result.pull_frames = static_cast<int>(frames.size());
  result.pull_duration_s = frames.back().time_s;
  result.pull_stats = reader.stats();
  if (result.sensor.empty()) result.sensor = SensorName(reader);
}

// Another layout's recording, pass 1: the sharpest still frame, scored as a .mkv's captures.
ScanViewPick ScoreSequenceScan(const fs::path& recording, const RgbdSequence& sequence,
                               const CaptureFromOptions& options) {
  std::vector<double> sharpness, motion_to_previous;
  std::optional<SmallGrey> previous;
  Progress progress("score " + recording.filename().string(), static_cast<int64_t>(sequence.size()),
                    "frames");
  for (size_t i = 0; i < sequence.size(); ++i) {
    const RgbImage color = sequence.LoadColor(i);
    SmallGrey grey = azure_detail::Shrink(color);
    motion_to_previous.push_back(previous ? azure_detail::Motion(*previous, grey) : -1.0);
    previous = std::move(grey);
    sharpness.push_back(azure_detail::Sharpness(color));
    progress.Advance();
  }
  progress.Done();
  int best = 0;
  ScanViewPick pick = PickStillFrame(recording, sharpness, motion_to_previous, options, &best);
  pick.capture = best;
  pick.timestamp_us = std::llround((sequence.time_s(best) - sequence.time_s(0)) * 1e6);
  return pick;
}

// Another layout's recording as pull/: every frame, its time from the first; frame numbers follow
// the times as for a .mkv.
void WriteSequencePull(const fs::path& recording, const RgbdSequence& sequence,
                       const CaptureFromOptions& options, const fs::path& capture_root,
                       CaptureFromResult& result) {
  const fs::path pull = capture_root / "pull";
  fs::create_directories(pull);
  WriteIntrinsicsJson(sequence.intrinsics(), pull / "intrinsics.json");
  std::vector<PullFrame> frames;
  FrameNumbering numbering;
  size_t count = sequence.size();
  if (options.max_pull_frames > 0) count = std::min<size_t>(count, options.max_pull_frames);
  Progress progress("pull " + recording.filename().string(), static_cast<int64_t>(count), "frames");
  for (size_t i = 0; i < count; ++i) {
    const RgbdImage rgbd = sequence.Load(i);
    if (i == 0 && options.write_check_images) WriteCheckImage(rgbd, capture_root, "pull_first");
    const double time_s = sequence.time_s(i) - sequence.time_s(0);
    frames.push_back(WritePullFrame(pull, numbering.Next(std::llround(time_s * 1e6)), time_s,
                                    rgbd.color, rgbd.depth, options.png));
    progress.Advance();
  }
  progress.Done();
  if (options.snap_pull_times) result.pull_time_snap_max_s = SnapTimes(frames);
  WriteFramesCsv(frames, pull / "frames.csv");
  result.pull_frames = static_cast<int>(frames.size());
  result.pull_duration_s = frames.back().time_s;
  result.pull_stats.captures = static_cast<int>(count);
  result.pull_stats.color_frames = result.pull_stats.depth_frames = static_cast<int>(count);
  if (frames.size() > 1 && frames.back().frame > 0) {
    result.pull_stats.frame_rate_hz = frames.back().frame / frames.back().time_s;
  }
  if (result.sensor.empty()) result.sensor = sequence.sensor();
}

RecordingLayout LayoutOf(const fs::path& recording, const CaptureFromOptions& options) {
  return options.layout == RecordingLayout::kAuto ? DetectLayout(recording) : options.layout;
}

// One scan view from a recording of any layout.
ScanViewPick WriteView(const fs::path& recording, const std::string& view,
                       const CaptureFromOptions& options, const fs::path& capture_root,
                       CaptureFromResult& result) {
  if (LayoutOf(recording, options) == RecordingLayout::kAzureMkv) {
    ScanViewPick pick = ScoreScan(recording, options);
    pick.view = view;
    WriteScan(pick, options, capture_root);
    if (result.sensor.empty()) result.sensor = SensorName(AzureKinectReader(pick.recording));
    return pick;
  }
  const auto sequence = OpenRgbdSequence(recording, options.layout, options.sequence);
  ScanViewPick pick = ScoreSequenceScan(recording, *sequence, options);
  pick.view = view;
  const RgbdImage rgbd = sequence->Load(pick.capture);
  WriteScanView(capture_root, view, rgbd, options.png);
  if (options.write_check_images) WriteCheckImage(rgbd, capture_root, view);
  if (result.sensor.empty()) result.sensor = sequence->sensor();
  return pick;
}

}  // namespace

void CaptureFromOptions::Validate() const {
  CheckOption(!scans.empty() || pull.has_value(), "capture-from options", "scans",
              "expected at least one scan recording or a pull recording");
  CheckNonNegative("still_motion_grey", still_motion_grey);
  CheckAtLeast("max_pull_frames", max_pull_frames, 0);
  CheckOption(reader.read_color && reader.read_depth, "capture-from options", "reader",
              "expected colour and depth to be read");
  reader.Validate();
  registration.Validate();
  CheckNested("sequence", sequence);
}

CaptureFromResult CaptureFromRecordings(const CaptureFromOptions& options,
                                        const fs::path& capture_root) {
  options.Validate();
  CaptureFromResult result;
  fs::create_directories(capture_root);
  for (size_t i = 0; i < options.scans.size(); ++i) {
    result.views.push_back(
        WriteView(options.scans[i], fmt::format("view_{:02d}", i), options, capture_root, result));
  }
  if (options.pull) {
    result.pull_layout = LayoutOf(*options.pull, options);
    if (result.pull_layout == RecordingLayout::kAzureMkv) {
      WritePull(*options.pull, options, capture_root, result);
    } else {
      const auto sequence = OpenRgbdSequence(*options.pull, options.layout, options.sequence);
      WriteSequencePull(*options.pull, *sequence, options, capture_root, result);
    }
  }
  CaptureInfo info;
  info.sensor = result.sensor;
  info.notes =
      "converted from recordings by simtree capture-from; pull/markers.json "
      "and pull/init.json are the user's to write";
  WriteCaptureInfo(info, capture_root / "capture.json");
  return result;
}

}  // namespace simtree
