#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/option_checks.h"
#include "simtree/io/capture_from_recordings.h"
#include "simtree/io/intrinsics_file.h"
#include "simtree/io/tum_rgbd.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace simtree::cli {

namespace {

// A recording folder is read whole (its layout from what it holds): a capture written inside one
// would change the input, and a second run would meet it there.
void RefuseOutputInsideRecordings(const fs::path& output, const std::vector<fs::path>& inputs) {
  std::error_code ec;
  const fs::path out = fs::weakly_canonical(output, ec);
  for (const fs::path& input : inputs) {
    if (!fs::is_directory(input)) continue;
    const fs::path rel = out.lexically_relative(fs::weakly_canonical(input, ec));
    if (!rel.empty() && rel.native().rfind("..", 0) != 0) {
      throw InputError(output.string(), "",
                       fmt::format("refusing to write inside the recording {}; choose another "
                                   "output",
                                   input.string()));
    }
  }
}

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
    if (r.pull_layout == RecordingLayout::kAzureMkv) {
      spdlog::info(
          "pull: {} frames over {:.2f} s ({:.1f} fps); {} captures without colour or "
          "depth skipped; dropped by the camera: {} colour, {} depth",
          r.pull_frames, r.pull_duration_s, s.frame_rate_hz, r.pull_skipped, s.dropped_color,
          s.dropped_depth);
    } else {
      spdlog::info("pull: {} frames over {:.2f} s ({:.1f} fps, {} layout)", r.pull_frames,
                   r.pull_duration_s, s.frame_rate_hz, LayoutName(r.pull_layout));
    }
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
    std::string pull, output, layout = "auto", intrinsics, camera;
    double depth_scale = 0;
    CaptureFromOptions options;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "capture-from",
      "RGB-D recordings to a capture folder: each scan recording becomes a view (its sharpest "
      "still capture), the pull recording pull/ (the recording's timestamps). A recording is an "
      "Azure Kinect .mkv (k4arecorder; colour undistorted, depth registered into it), a "
      "RealSense .bag (depth aligned to colour), a TUM "
      "RGB-D folder (rgb.txt, depth.txt; give the camera) or an Open3D folder (color/, depth/, "
      "intrinsic.json). pull/markers.json and pull/init.json are yours to write afterwards "
      "(docs/formats.md)");
  verb->add_option("scans", args->scans, "Scan recordings, one per view, in view order")
      ->check(CLI::ExistingPath);
  verb->add_option("--pull", args->pull, "The pull test's recording (a fixed camera)")
      ->check(CLI::ExistingPath);
  verb->add_option("--layout", args->layout,
                   "Every recording's layout: auto (from the path: .mkv, .bag, a folder with "
                   "rgb.txt, a folder with depth/ and intrinsic.json), mkv, bag, tum, open3d")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "mkv", "bag", "tum", "open3d"}));
  verb->add_option("--intrinsics", args->intrinsics,
                   "Camera of TUM or Open3D recordings: simtree's intrinsics.json or Open3D's "
                   "PinholeCameraIntrinsic JSON (TUM's lists carry none; replaces an Open3D "
                   "folder's own)")
      ->check(CLI::ExistingFile);
  verb->add_option("--camera", args->camera,
                   "One of TUM's published colour cameras (640x480) instead of --intrinsics: "
                   "tum-fr1, tum-fr2 (both keep their lens distortion), tum-fr3, tum-default")
      ->check(CLI::IsMember(TumCameraNames()));
  verb->add_option("--depth-scale", args->depth_scale,
                   "Depth units per metre of TUM, Open3D or .bag depth images (default: TUM 5000, "
                   "Open3D 1000, a .bag's Depth Units option); written as millimetres")
      ->check(CLI::PositiveNumber);
  verb->add_option("--max-time-difference", args->options.sequence.max_time_difference_s,
                   "TUM, .bag: pair colour and depth frames at most this many seconds apart")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_option("--fps", args->options.sequence.fps,
                   "Open3D folders carry no times: frame i is at i / fps seconds")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
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
       "simtree capture-from --pull rgbd_dataset_freiburg3_walking_static --camera tum-fr3 "
       "--out capture/   # a TUM RGB-D sequence as the pull stream",
       "simtree capture-from north/ east/ south/ --pull pull/ --out capture/   # Open3D folders "
       "(color/, depth/, intrinsic.json)",
       "simtree capture-from --pull pull.bag --out capture/   # a RealSense recording, depth "
       "aligned to colour",
       "simtree capture-from seq_a/ --intrinsics k.json --depth-scale 1000 --layout tum --out "
       "capture/",
       "then write capture/pull/markers.json and capture/pull/init.json and run "
       "`simtree run capture/ --out result/`"}));
  verb->callback([args] {
    std::vector<fs::path> inputs(args->scans.begin(), args->scans.end());
    for (const fs::path& p : inputs) args->options.scans.push_back(p);
    if (!args->pull.empty()) {
      args->options.pull = args->pull;
      inputs.push_back(args->pull);
    }
    args->options.layout = ParseLayout(args->layout);
    if (!args->intrinsics.empty() && !args->camera.empty()) {
      throw OptionError("--camera", "expected --intrinsics or --camera, not both");
    }
    if (!args->intrinsics.empty()) {
      args->options.sequence.intrinsics = ReadIntrinsicsFile(args->intrinsics);
    }
    if (!args->camera.empty()) args->options.sequence.intrinsics = TumCamera(args->camera);
    if (args->depth_scale > 0) args->options.sequence.depth_units_per_m = args->depth_scale;
    args->options.Validate();
    RefuseToOverwriteInputs(args->output, inputs);
    RefuseOutputInsideRecordings(args->output, inputs);
    AtomicDirectory folder(args->output);
    const CaptureFromResult result = CaptureFromRecordings(args->options, folder.path());
    folder.Commit();
    LogResult(result, args->output);
  });
}

}  // namespace simtree::cli
