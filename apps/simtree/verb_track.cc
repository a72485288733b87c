#include <filesystem>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/io/track_init.h"
#include "simtree/tracking/track.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace simtree::cli {
namespace {

struct TrackArgs {
  std::string pull, out, init, motion = "constant_velocity";
  bool overlay = false, video = false;
  tracking::TrackOptions options;
};

void AddTrackOptions(CLI::App* verb, TrackArgs& a) {
  verb->add_option("pull", a.pull,
                   "The pull-test stream: a capture's pull/ folder (intrinsics.json, frames.csv, "
                   "markers.json, color/, depth/), or the capture folder holding it")
      ->required()
      ->check(CLI::ExistingDirectory);
  verb->add_option("-o,--out", a.out,
                   "Folder to write: trajectories.csv, boxes.csv, track_summary.json, markers.json "
                   "(copied for identify), overlay/ and overlay.mp4 when asked")
      ->required();
  verb->add_option("--init", a.init,
                   "init.json (simtree.track_init): each marker's pixel in one frame (default: "
                   "init.json in the pull folder)")
      ->check(CLI::ExistingFile);
  verb->add_option("--color", a.options.color,
                   "Tape colour: auto (red, fitted to the init pixels), red, orange, yellow, "
                   "green, blue or #rrggbb")
      ->capture_default_str();
  verb->add_option("--motion", a.motion,
                   "Motion model per marker: constant_velocity or damped_oscillator")
      ->capture_default_str()
      ->check(CLI::IsMember({"constant_velocity", "damped_oscillator"}));
  verb->add_option("--max-coast", a.options.max_coast_frames,
                   "Frames a marker coasts on its prediction before it is called lost")
      ->capture_default_str();
  verb->add_option("--process-noise", a.options.process_noise_mps2,
                   "Acceleration noise of the motion model (m/s^2): larger follows faster swings")
      ->capture_default_str();
  verb->add_option("--gate-mm", a.options.gate_mm,
                   "Largest 3D jump (mm) between a marker's prediction and its detection")
      ->capture_default_str();
  verb->add_flag("--overlay", a.overlay,
                 "Write overlay/NNNNNN.png: boxes (green tracked, yellow predicted), ids, trails");
  verb->add_flag("--video", a.video,
                 "Write overlay.mp4 (H.264 through the ffmpeg program; implies --overlay)");
  verb->add_option("--threads", a.options.threads, "Threads loading frames (0: all cores)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
}

void RunTrack(TrackArgs& a) {
  fs::path pull = a.pull;
  if (!fs::exists(pull / "frames.csv") && fs::exists(pull / "pull" / "frames.csv")) pull /= "pull";
  const fs::path init_path = a.init.empty() ? pull / "init.json" : fs::path(a.init);
  if (!fs::exists(init_path)) {
    throw InputError(init_path.string(), "",
                     "expected init.json (each marker's pixel in the first frame, "
                     "docs/formats.md); give one with --init");
  }
  RefuseToOverwriteInputs(a.out, {pull, init_path});
  a.options.motion_model = a.motion == "damped_oscillator"
                               ? tracking::MotionModelKind::kDampedOscillator
                               : tracking::MotionModelKind::kConstantVelocity;
  const TrackInit init = ReadTrackInitJson(init_path);
  const tracking::TrackResult result = tracking::Track(pull, init, a.options);
  tracking::WriteTrackOutputs(result, a.out,
                              tracking::TrackOutputOptions{.overlay = a.overlay, .video = a.video});
  for (const std::string& w : result.warnings) spdlog::warn("{}", w);
  for (const tracking::FlaggedFrame& f : result.flagged) {
    spdlog::warn("frame {}: {}", f.frame, f.reason);
  }
  int tracked = 0, total = 0;
  for (const tracking::MarkerCounts& c : result.counts) {
    tracked += c.tracked;
    total += c.tracked + c.predicted + c.lost;
  }
  fmt::print(
      "tracked {} markers over {} frames: {:.1f}% of marker-frames measured, {} flagged "
      "frames; colour model {}; wrote {}\n",
      result.counts.size(), result.trajectories.frame_count(),
      total > 0 ? 100.0 * tracked / total : 0.0, result.flagged.size(), result.color_model, a.out);
}

}  // namespace

void RegisterTrack(CLI::App& app) {
  auto args = std::make_shared<TrackArgs>();
  CLI::App* verb = app.add_subcommand(
      "track",
      "Track the tape markers through a pull-test stream in 3D (paper III-C): per frame each "
      "marker's centre in the camera frame (trajectories.csv, valid 0 where not measured) and "
      "the box of its tape band (boxes.csv)");
  AddTrackOptions(verb, *args);
  verb->footer(Examples({
      "simtree track capture/pull --out tracks/",
      "simtree track capture/pull --init my_init.json --out tracks/ --overlay --video",
      "simtree track capture/pull --out tracks/ --color '#1060e0' --threads 2",
      "simtree identify tracks/ --out materials.json",
  }));
  verb->callback([args] { RunTrack(*args); });
}

}  // namespace simtree::cli
