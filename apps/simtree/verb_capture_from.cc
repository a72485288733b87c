#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/io/capture_from_recordings.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace simtree::cli {

namespace {

void LogResult(const CaptureFromResult& r, const std::string& output) {
  for (const ScanViewPick& v : r.views) {
    spdlog::info(
        "{}: {} capture {} at {:.3f} s (sharpest of {} still of {} captures; motion "
        "{:.2f} grey levels)",
        v.view, v.recording.string(), v.capture, v.timestamp_us * 1e-6, v.still, v.candidates,
        v.motion_grey);
  }
  if (r.pull_frames > 0) {
    const AzureReadStats& s = r.pull_stats;
    spdlog::info(
        "pull: {} frames over {:.2f} s ({:.1f} fps); {} captures without colour or "
        "depth skipped; dropped by the camera: {} colour, {} depth",
        r.pull_frames, r.pull_duration_s, s.frame_rate_hz, r.pull_skipped, s.dropped_color,
        s.dropped_depth);
    if (r.pull_time_snap_max_s > 0) {
      spdlog::info("pull: times snapped to a regular grid, moved by at most {:.2f} ms",
                   r.pull_time_snap_max_s * 1e3);
    }
    spdlog::info(
        "now write {0}/pull/markers.json (the tape markers and their links) and "
        "{0}/pull/init.json (each marker's pixel in the first frame): docs/formats.md",
        output);
  }
  spdlog::info("wrote {} ({})", output, r.sensor);
}

}  // namespace

void RegisterCaptureFrom(CLI::App& app) {
  struct Args {
    std::vector<std::string> scans;
    std::string pull, output;
    CaptureFromOptions options;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "capture-from",
      "Azure Kinect recordings (k4arecorder .mkv) to a capture folder: each scan recording "
      "becomes a view (its sharpest still capture), the pull recording pull/ (colour undistorted, "
      "depth registered into it, the recording's timestamps). pull/markers.json and "
      "pull/init.json are yours to write afterwards (docs/formats.md)");
  verb->add_option("scans", args->scans, "Scan recordings, one per view, in view order")
      ->check(CLI::ExistingFile);
  verb->add_option("--pull", args->pull, "The pull test's recording (a fixed camera)")
      ->check(CLI::ExistingFile);
  verb->add_option("-o,--out", args->output, "Capture folder to write")->required();
  verb->add_option("--still-motion", args->options.still_motion_grey,
                   "A scan capture counts as still when it changes at most this many grey levels "
                   "(mean, 0-255) from its neighbours, or moves no more than the quarter that "
                   "move least")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_option("--max-pull-frames", args->options.max_pull_frames,
                   "Keep only the first N pull captures (0: all)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_flag("--snap-times", args->options.snap_pull_times,
                 "Put pull frame k at k x the mean frame period: for recordings with millisecond "
                 "timestamps (written by libav, e.g. capture-export), whose 33/34 ms steps "
                 "identify refuses");
  verb->add_flag("--check", args->options.write_check_images,
                 "Also write check/<view>.png and check/pull_first.png: colour blended with "
                 "depth, and colour with depth edges in green (they must follow the outlines)");
  verb->footer(Examples(
      {"simtree capture-from north.mkv east.mkv south.mkv west.mkv --pull "
       "pull.mkv --out capture/",
       "simtree capture-from scans/*.mkv --out capture/ --check   # scans only, check images",
       "then write capture/pull/markers.json and capture/pull/init.json and run "
       "`simtree run capture/ --out result/`"}));
  verb->callback([args] {
    std::vector<fs::path> inputs(args->scans.begin(), args->scans.end());
    for (const fs::path& p : inputs) args->options.scans.push_back(p);
    if (!args->pull.empty()) {
      args->options.pull = args->pull;
      inputs.push_back(args->pull);
    }
    args->options.Validate();
    RefuseToOverwriteInputs(args->output, inputs);
    AtomicDirectory folder(args->output);
    const CaptureFromResult result = CaptureFromRecordings(args->options, folder.path());
    folder.Commit();
    LogResult(result, args->output);
  });
}

}  // namespace simtree::cli
