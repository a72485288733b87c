#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "scene_options.h"
#include "sim_options.h"
#include "simtree/core/error.h"
#include "simtree/dynamics/recorders.h"
#include "simtree/io/ground_truth.h"
#include "simtree/viewer/marker_playback.h"
#include "simtree/viewer/view.h"
#include "verbs.h"

namespace simtree::cli {
namespace {

struct ViewArgs {
  SceneArgs scene;
  SimulationArgs run;
  std::string script, tracks, camera_pose, screenshots = ".";
  std::vector<int> size = {1280, 800};
  int msaa = 0;
  int marker_level = 2;
  bool paused = false, fixed_step = false, vsync = false;
};

void AddWindowOptions(CLI::App* verb, ViewArgs& args) {
  auto* window = verb->add_option_group("window");
  window->add_option("--size", args.size, "Window size WIDTH,HEIGHT in pixels")
      ->expected(2)
      ->delimiter(',')
      ->capture_default_str();
  window->add_option("--msaa", args.msaa, "Anti-aliasing samples (0 = off; slow without a GPU)")
      ->capture_default_str()
      ->check(CLI::Range(0, 16));
  window->add_flag("--vsync", args.vsync, "Wait for the display's refresh");
  window->add_flag("--paused", args.paused, "Start with the simulation paused");
  window->add_flag("--fixed-step", args.fixed_step,
                   "Advance 1/fps simulated seconds per drawn frame, however long it takes");
  window
      ->add_option("--screenshots", args.screenshots,
                   "Folder for screenshots taken with the p key or the panel button")
      ->capture_default_str();
  window
      ->add_option("--script", args.script,
                   "Scripted input, one action a line: pick X Y, pick-branch B[@S], drag X Y "
                   "[FRAMES], release, hover X Y, wait N, screenshot PATH, key K, play, pause, "
                   "step, reset, wind on|off|SPEED, leaves on|off, material branch|level ID "
                   "frequency|damping|stiffness V, orbit DYAW DPITCH, zoom F, quit")
      ->check(CLI::ExistingFile);
}

void AddPlaybackOptions(CLI::App* verb, ViewArgs& args) {
  auto* playback = verb->add_option_group("playback");
  playback
      ->add_option("--tracks", args.tracks,
                   "Measured marker tracks to show beside the simulated markers: "
                   "trajectories.csv from `track` (camera frame, needs --camera-pose) or the "
                   "world-frame markers.csv of `simulate`")
      ->check(CLI::ExistingFile);
  playback
      ->add_option("--camera-pose", args.camera_pose,
                   "The pull camera's pose (world_from_camera JSON, as gt/pull_camera.json)")
      ->check(CLI::ExistingFile);
  playback
      ->add_option("--marker-level", args.marker_level,
                   "For a tree without markers: tip markers up to this level, as `simulate` "
                   "places them")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
}

void AddViewOptions(CLI::App* verb, ViewArgs& args) {
  AddTreeInput(verb, args.scene);
  AddPullOptions(verb, args.run);
  AddWindOptions(verb, args.run);
  AddModelOptions(verb, args.run);
  AddSceneOptions(verb, args.scene);
  verb->add_option("--fps", args.run.sim.fps,
                   "Simulation frames per second with --fixed-step (and scripts)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  AddWindowOptions(verb, args);
  AddPlaybackOptions(verb, args);
  verb->footer(Examples({
      "simtree view tree02.txt",
      "simtree view tree01.txt --material-file tree_parameters.txt --leaves none",
      "simtree view tree.json --pull 3 --force 100 --release 3 --tracks sim/markers.csv",
      "simtree view tree.json --script actions.txt   # pick-branch 5, drag 700 500 20, wait 30, "
      "screenshot a.png, release, quit",
  }));
}

// The measured tracks to play back, and the simulated markers they are compared with: the tree's
// own, or for a tree without markers the ones `simulate` tracks.
void AddPlayback(const Tree& tree, const ViewArgs& args, viewer::ViewerOptions& options) {
  options.markers = tree.markers;
  if (args.tracks.empty()) return;
  std::optional<Eigen::Isometry3d> pose;
  if (!args.camera_pose.empty()) pose = ReadPullCamera(args.camera_pose);
  options.measured = viewer::ReadTracksInWorld(args.tracks, pose);
  if (options.markers.empty()) {
    std::optional<dynamics::Rope> rope;
    if (options.pull) rope = options.pull->rope;
    options.markers = dynamics::AutoMarkers(tree, args.marker_level, rope);
  }
}

viewer::ViewerOptions ViewerOptionsFromArgs(const Tree& tree, const ViewArgs& args) {
  viewer::ViewerOptions options;
  options.width = args.size[0];
  options.height = args.size[1];
  options.samples = args.msaa;
  options.vsync = args.vsync;
  options.title = "simtree view " + args.scene.input;
  options.style = StyleFromArgs(args.scene);
  options.dynamics = args.run.sim.dynamics;
  options.pull = args.run.sim.pull;
  options.fps = args.run.sim.fps;
  options.start_paused = args.paused;
  options.screenshot_dir = args.screenshots;
  options.fixed_step = args.fixed_step;
  if (!args.script.empty()) {
    options.script = viewer::ReadScript(args.script);
    options.script_source = args.script;
    options.fixed_step = true;  // a script means the same motion however fast frames are drawn
  }
  AddPlayback(tree, args, options);
  return options;
}

void View(ViewArgs& args) {
  if (args.size[0] < 64 || args.size[1] < 64) {
    throw InputError("", "--size", "expected a window of at least 64x64 pixels");
  }
  const Tree tree = LoadTreeForViewing(args.scene);
  FinishSimulationArgs(tree, args.run);
  const viewer::ViewerOptions options = ViewerOptionsFromArgs(tree, args);
  options.Validate();
  const viewer::SceneAssets assets =
      viewer::LoadSceneAssets(tree, args.scene.input, args.scene.foliage);
  viewer::Viewer viewer(tree, assets, options);
  viewer.Run();
  const viewer::ViewerStats& stats = viewer.stats();
  spdlog::info(
      "view: {} frames, {:.1f} ms a frame on average ({:.1f} ms drawing, {:.1f} ms "
      "simulating)",
      stats.frames, stats.mean_frame_ms, stats.mean_draw_ms, stats.mean_simulate_ms);
}

}  // namespace

void RegisterView(CLI::App& app) {
  auto args = std::make_shared<ViewArgs>();
  CLI::App* verb = app.add_subcommand(
      "view",
      "Interactive window: pull and release branches with the mouse, wind, tune frequency, "
      "damping and stiffness live, play tracked markers back against the simulation");
  AddViewOptions(verb, *args);
  verb->callback([args] { View(*args); });
}

}  // namespace simtree::cli
