// The pull stream's checks: its timing, and its first frame with the tape markers.

#include <algorithm>
#include <filesystem>

#include <fmt/format.h>

#include "simtree/capture_check/detail/grade.h"
#include "simtree/capture_check/detail/steps.h"
#include "simtree/capture_check/detail/tape_check.h"
#include "simtree/core/error.h"
#include "simtree/io/track_init.h"

namespace simtree::capture_check::detail {

namespace {

void CheckTiming(const PullStream& pull, const CheckThresholds& t, std::vector<Check>* out) {
  const std::vector<PullFrame>& f = pull.frames;
  const int n = static_cast<int>(f.size());
  const double duration = n > 1 ? f.back().time_s - f.front().time_s : 0;
  const double rate = pull.FrameRate();
  int dropped = 0, longest = 0;
  for (int i = 1; i < n; ++i) {
    const int skipped = f[i].frame - f[i - 1].frame - 1;
    dropped += skipped;
    longest = std::max(longest, skipped);
  }
  if (n < 2) {
    out->push_back(Failed("frame rate", "pull",
                          fmt::format("{} frame: record the whole pull test, still tree, pull, "
                                      "release and 10 s or more of free swinging",
                                      n)));
    return;
  }
  out->push_back(Grade("frame rate", "pull", rate, "fps",
                       {Better::kHigher, t.warn_frame_rate_hz, t.fail_frame_rate_hz},
                       fmt::format("{} frames at {:.1f} fps", n, rate),
                       "record at 30 fps: identify needs at least 2 frames a period of the "
                       "fastest branch (up to 10 Hz), and the tracker small steps"));
  out->push_back(Grade("pull length", "pull", duration, "s",
                       {Better::kHigher, t.warn_duration_s, t.warn_duration_s},
                       fmt::format("{:.1f} s recorded", duration),
                       "record until the branches are still again (10 s or more after the "
                       "release): a short free decay resolves light damping poorly"));
  const double share = n > 0 ? static_cast<double>(dropped) / (dropped + n) : 0;
  out->push_back(Grade("dropped frames", "pull", share, "%",
                       {Better::kLower, 0, t.fail_dropped_share},
                       fmt::format("{} frames dropped (longest gap {} frames)", dropped, longest),
                       "the recorder could not keep up: record to a fast local disk, close "
                       "other programs, use a USB 3 port of its own",
                       100));
}

// The frame the tracker starts from: init.json's when it names one in the stream, else the first.
size_t StartFrame(const PullStream& pull) {
  const std::filesystem::path init = pull.directory / "init.json";
  if (!std::filesystem::exists(init)) return 0;
  const int number = ReadTrackInitJson(init).frame;
  for (size_t i = 0; i < pull.frames.size(); ++i) {
    if (pull.frames[i].frame == number) return i;
  }
  return 0;
}

// The median tape's width, warned also when some tapes are narrower than the fail limit.
Check TapeWidthCheck(const TapeCheck& tape, const CheckThresholds& t, const std::string& subject) {
  const int thin = static_cast<int>(std::count_if(tape.widths_px.begin(), tape.widths_px.end(),
                                                  [&](double w) { return w < t.fail_tape_px; }));
  std::string found = fmt::format("the tapes are {:.1f} px wide (median; narrowest {:.1f} px)",
                                  tape.median_px, tape.narrowest_px);
  if (thin > 0)
    found += fmt::format(", {} of {} below {:g} px", thin, tape.widths_px.size(), t.fail_tape_px);
  Check c = Grade("tape width", subject, tape.median_px, "px",
                  {Better::kHigher, t.warn_tape_px, t.fail_tape_px}, found,
                  fmt::format("move closer or use wider tape: the tracker loses tapes under "
                              "{:g} px (docs/capturing.md gives the width for your distance)",
                              t.warn_tape_px));
  if (c.status == Status::kOk && thin > 0) {
    c.status = Status::kWarn;
    c.message = found + ": the thinnest tapes will be lost: move closer or use wider tape there";
  }
  return c;
}

void CheckTape(const RgbdImage& image, const PullStream& pull, int frame_number,
               const CaptureCheckOptions& options, const std::string& subject,
               std::vector<Check>* out) {
  const CheckThresholds& t = options.thresholds;
  const TapeCheck tape = MeasureTape(image, pull, frame_number, options.tape_color);
  if (tape.found == 0) {
    out->push_back(Failed(
        "tape markers", subject,
        fmt::format("no tape of the colour '{}' found{}: wrap saturated tape (red) all around "
                    "the branches, facing the camera, and check --color",
                    options.tape_color, tape.has_init ? " at init.json's pixels" : "")));
    return;
  }
  const std::string of = tape.expected > 0 ? fmt::format(" of {}", tape.expected) : "";
  const double expected = tape.expected > 0 ? tape.expected : tape.found;
  out->push_back(Grade("tape markers", subject, tape.found, "", {Better::kHigher, expected, 1},
                       fmt::format("{}{} markers show their tape{}", tape.found, of,
                                   tape.has_init ? " at init.json's pixels" : ""),
                       "markers without tape in view start lost: turn the tape to face the "
                       "camera, or move the camera so twigs do not hide it"));
  out->push_back(TapeWidthCheck(tape, t, subject));
}

}  // namespace

void CheckPull(const Capture& capture, const CaptureCheckOptions& options,
               std::vector<Check>* out) {
  if (!capture.pull) {
    out->push_back(Skipped("pull stream", "pull", "no pull/ folder: no pull test to check"));
    return;
  }
  const PullStream& pull = *capture.pull;
  CheckTiming(pull, options.thresholds, out);
  if (pull.frames.empty()) return;
  const size_t index = StartFrame(pull);
  const std::string subject = fmt::format("pull frame {}", pull.frames[index].frame);
  RgbdImage image;
  try {
    image = LoadPullFrame(pull, index);
  } catch (const Error& e) {
    out->push_back(Failed("images", subject, e.what()));
    return;
  }
  CheckFrame(subject, image, preprocessing::PreprocessPullFrame(capture, index), options.thresholds,
             out);
  CheckTape(image, pull, pull.frames[index].frame, options, subject, out);
}

}  // namespace simtree::capture_check::detail
