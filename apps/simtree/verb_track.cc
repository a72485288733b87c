#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/tree_json.h"
#include "simtree/io/track_init.h"
#include "simtree/tracking/camera_pose_file.h"
#include "simtree/tracking/init_from_tree.h"
#include "simtree/tracking/track.h"
#include "simtree/viewer/pick_markers.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace simtree::cli {
namespace {

struct TrackArgs {
  std::string pull, out, init, motion = "constant_velocity";
  std::string init_from, pull_pose, pick_script;
  bool overlay = false, video = false, init_only = false, pick = false;
  tracking::TrackOptions options;
  tracking::InitFromTreeOptions from_tree;
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
  CLI::Option* from = verb->add_option(
      "--init-from", a.init_from,
      "A tree carrying its markers' 3D positions (simtree.tree: gt/tree.json, an earlier "
      "run's build/simready.json): each marker is projected into the first frame with "
      "--pull-pose and matched to a tape blob; writes init.json into --out and tracks from it");
  from->check(CLI::ExistingFile)->excludes("--init");
  verb->add_option("--pull-pose", a.pull_pose,
                   "The pull camera's pose in that tree's frame: register's pull_camera.json "
                   "(simtree.pull_camera) or {\"world_from_camera\": [16 numbers]}")
      ->check(CLI::ExistingFile)
      ->needs(from);
  from->needs("--pull-pose");
  verb->add_option("--pose-error-deg", a.from_tree.pose_rotation_deg,
                   "With --init-from: how many degrees the pose may be off (widens the search)")
      ->capture_default_str()
      ->needs(from);
  verb->add_option("--pose-error-m", a.from_tree.pose_translation_m,
                   "With --init-from: how many metres the pose may be off")
      ->capture_default_str()
      ->needs(from);
  CLI::Option* pick =
      verb->add_flag("--pick", a.pick,
                     "Open the first frame in a window and click each marker of markers.json in "
                     "turn (wheel zooms, right-drag pans, Backspace undoes, S skips, Enter "
                     "finishes); writes init.json into --out and tracks from it");
  pick->excludes("--init")->excludes(from);
  verb->add_option("--pick-script", a.pick_script,
                   "With --pick: scripted clicks and keys instead of the user's (for tests; "
                   "docs/tracking.md#initialisation)")
      ->check(CLI::ExistingFile)
      ->needs(pick);
  verb->add_flag("--init-unmatched", a.from_tree.keep_unmatched,
                 "With --init-from: a marker with no tape blob near its projection starts at the "
                 "corrected projection (the tracker starts it lost) instead of being left out")
      ->needs(from);
  verb->add_flag("--init-only", a.init_only,
                 "Write --out/init.json (--init-from or --pick) and stop before tracking");
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

// Projects the tree's markers into the first frame, writes out/init.json and says what became
// of each marker.
fs::path InitFromTree(const TrackArgs& a, const fs::path& pull) {
  RefuseToOverwriteInputs(a.out, {pull, a.init_from, a.pull_pose});
  const Tree tree = ReadTreeJson(a.init_from);
  const Eigen::Isometry3d pose = tracking::ReadCameraPoseJson(a.pull_pose);
  tracking::InitFromTreeOptions options = a.from_tree;
  options.color = a.options.color;
  const tracking::InitFromTreeResult r =
      tracking::InitFromTree(pull, tree, pose, options, a.init_from);
  for (const std::string& w : r.warnings) spdlog::warn("{}", w);
  const fs::path path = fs::path(a.out) / "init.json";
  fs::create_directories(a.out);
  WriteTrackInitJson(r.init, path);
  const auto count = [&](tracking::MarkerInitStatus s) {
    return std::count_if(r.markers.begin(), r.markers.end(),
                         [&](const tracking::MarkerInit& m) { return m.status == s; });
  };
  fmt::print(
      "init from the tree: {} of {} markers matched to {} tape blobs, {} at their projection "
      "(pose corrected by ({:.1f}, {:.1f}) px, {:.2f} deg, scale {:.3f}, gate {:.1f} px); "
      "wrote {}\n",
      count(tracking::MarkerInitStatus::kMatched), r.markers.size(), r.blobs,
      count(tracking::MarkerInitStatus::kProjected), r.shift_px.x(), r.shift_px.y(), r.rotation_deg,
      r.scale, r.match_radius_px, path.string());
  return path;
}

// Lets the user click each marker in the first frame and writes out/init.json.
fs::path PickInit(const TrackArgs& a, const fs::path& pull) {
  RefuseToOverwriteInputs(a.out, {pull});
  viewer::MarkerPickOptions options;
  if (!a.pick_script.empty()) {
    options.script = viewer::detail::ReadPickScript(a.pick_script);
    options.script_source = a.pick_script;
  }
  const viewer::MarkerPickResult r = viewer::PickMarkers(pull, options);
  const fs::path path = fs::path(a.out) / "init.json";
  fs::create_directories(a.out);
  WriteTrackInitJson(r.init, path);
  fmt::print("picked {} markers, skipped [{}]; wrote {}\n", r.init.markers.size(),
             fmt::join(r.skipped, ", "), path.string());
  return path;
}

void RunTrack(TrackArgs& a) {
  fs::path pull = a.pull;
  if (!fs::exists(pull / "frames.csv") && fs::exists(pull / "pull" / "frames.csv")) pull /= "pull";
  if (a.init_only && a.init_from.empty() && !a.pick) {
    throw InputError("--init-only", "", "needs --init-from or --pick (they write init.json)");
  }
  const fs::path init_path = !a.init_from.empty() ? InitFromTree(a, pull)
                             : a.pick             ? PickInit(a, pull)
                             : a.init.empty()     ? pull / "init.json"
                                                  : fs::path(a.init);
  if (a.init_only) return;
  if (!fs::exists(init_path)) {
    throw InputError(init_path.string(), "",
                     "expected init.json (each marker's pixel in the first frame, "
                     "docs/formats.md); give one with --init");
  }
  // An init made here lives in --out; only an init given is an input.
  if (a.init_from.empty() && !a.pick) RefuseToOverwriteInputs(a.out, {pull, init_path});
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
      "simtree track capture/pull --init-from capture/gt/tree.json --pull-pose "
      "capture/gt/pull_camera.json --out tracks/",
      "simtree track capture/pull --pick --out tracks/",
      "simtree identify tracks/ --out materials.json",
  }));
  verb->callback([args] { RunTrack(*args); });
}

}  // namespace simtree::cli
