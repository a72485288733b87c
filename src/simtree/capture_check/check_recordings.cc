// Recordings (any layout capture-from reads) checked through a capture folder made from them in a
// temporary folder, with what the conversion itself counted.

#include <chrono>
#include <filesystem>
#include <random>

#include <fmt/format.h>

#include "simtree/capture_check/capture_check.h"
#include "simtree/capture_check/detail/grade.h"

namespace fs = std::filesystem;

namespace simtree::capture_check {

namespace {

// A fresh folder under the system's temporary folder, removed when the object dies.
class ScratchFolder {
 public:
  ScratchFolder() {
    std::random_device seed;
    path_ = fs::temp_directory_path() / fmt::format("simtree-capture-check-{:08x}", seed());
    fs::create_directories(path_);
  }
  ~ScratchFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// The pull captures the conversion left out: the camera's drops within its tracks (a .mkv) and
// captures lacking colour or depth, which frames.csv does not show.
Check ConversionCheck(const CaptureFromResult& from, const CheckThresholds& t) {
  const int lost =
      from.pull_skipped + from.pull_stats.dropped_color + from.pull_stats.dropped_depth;
  const int all = from.pull_frames + lost;
  const double share = all > 0 ? static_cast<double>(lost) / all : 0;
  return detail::Grade(
      "recording drops", "pull recording", share, "%",
      {detail::Better::kLower, 0, t.fail_dropped_share},
      fmt::format("{} captures without colour or depth skipped; dropped by the camera: {} "
                  "colour, {} depth frames",
                  from.pull_skipped, from.pull_stats.dropped_color, from.pull_stats.dropped_depth),
      "the recorder could not keep up: record to a fast local disk, close other programs, use a "
      "USB 3 port of its own",
      100);
}

}  // namespace

CaptureCheckResult CheckRecordings(const CaptureFromOptions& recordings,
                                   const CaptureCheckOptions& options) {
  options.Validate();
  recordings.Validate();
  const auto start = std::chrono::steady_clock::now();
  ScratchFolder scratch;
  const CaptureFromResult from = CaptureFromRecordings(recordings, scratch.path());
  CaptureCheckResult result = CheckCapture(scratch.path(), options);
  result.capture = recordings.pull ? *recordings.pull : recordings.scans.front();
  if (recordings.pull) result.checks.push_back(ConversionCheck(from, options.thresholds));
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace simtree::capture_check
