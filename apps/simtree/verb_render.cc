#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "scene_options.h"
#include "sim_options.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/units.h"
#include "simtree/io/ground_truth.h"
#include "simtree/viewer/render.h"
#include "simtree/viewer/video.h"
#include "verbs.h"

namespace simtree::cli {

namespace {

struct RenderArgs {
  SceneArgs scene;
  SimulationArgs run;
  std::string output, video, capture, camera_pose, backend = "auto";
  std::vector<int> size = {1280, 720};
  int msaa = 4;
  double yaw_deg = -90.0, pitch_deg = 8.0, zoom = 1.0;
  bool no_markers = false;
};

void AddCameraOptions(CLI::App* verb, RenderArgs& args) {
  auto* camera = verb->add_option_group("camera");
  camera->add_option("--size", args.size, "Frame size WIDTH,HEIGHT in pixels")
      ->expected(2)
      ->delimiter(',')
      ->capture_default_str();
  camera
      ->add_option("--yaw-deg", args.yaw_deg,
                   "Where the camera stands, degrees counter-clockwise from +X around the tree "
                   "(-90: in front, looking along +Y)")
      ->capture_default_str();
  camera->add_option("--pitch-deg", args.pitch_deg, "Camera height angle above the horizon")
      ->capture_default_str();
  camera->add_option("--zoom", args.zoom, "Distance factor (< 1 comes closer)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  camera->add_option("--msaa", args.msaa, "Anti-aliasing samples (0 = off)")
      ->capture_default_str()
      ->check(CLI::Range(0, 16));
  camera
      ->add_option("--side-by-side", args.capture,
                   "Capture folder: its pull-test colour frames on the left, the simulation "
                   "from the pull camera on the right, at the capture's frame times")
      ->check(CLI::ExistingDirectory);
  camera
      ->add_option("--camera-pose", args.camera_pose,
                   "Pose JSON of the camera (world_from_camera, as gt/pull_camera.json); "
                   "default for --side-by-side: <capture>/gt/pull_camera.json")
      ->check(CLI::ExistingFile);
  camera->add_flag("--no-markers", args.no_markers, "Do not draw the tree's markers");
}

void AddRenderOptions(CLI::App* verb, RenderArgs& args) {
  AddTreeInput(verb, args.scene);
  verb->add_option("-o,--out", args.output,
                   "Frames folder: 000000.png, 000001.png, ... (replaced whole, or left "
                   "untouched on error)")
      ->required();
  verb->add_option("--video", args.video,
                   "Also encode the frames into this video (.mp4, H.264, through ffmpeg)");
  AddPullOptions(verb, args.run);
  AddRunOptions(verb, args.run);
  AddWindOptions(verb, args.run);
  AddModelOptions(verb, args.run);
  AddSceneOptions(verb, args.scene);
  AddCameraOptions(verb, args);
  verb->add_option("--backend", args.backend, "Headless OpenGL: auto (EGL, else Xvfb), egl or xvfb")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "egl", "xvfb"}));
  verb->footer(Examples({
      "simtree render tree02.txt --pull 20 --force 150 --release 2 --duration 6 --out frames/ "
      "--video pull.mp4",
      "simtree render tree.json --wind 8 --duration 10 --yaw-deg 0 --out windy/",
      "simtree render tree.json --pull 3 --force 80 --side-by-side capture/ --out fig15/ "
      "--video fig15.mp4",
  }));
}

viewer::RenderOptions RenderOptionsFromArgs(const RenderArgs& args) {
  viewer::RenderOptions options;
  options.width = args.size[0];
  options.height = args.size[1];
  options.samples = args.msaa;
  options.backend = args.backend == "egl"    ? viewer::OffscreenBackend::kEgl
                    : args.backend == "xvfb" ? viewer::OffscreenBackend::kXvfb
                                             : viewer::OffscreenBackend::kAuto;
  options.style = StyleFromArgs(args.scene);
  options.yaw_rad = DegToRad(args.yaw_deg);
  options.pitch_rad = DegToRad(args.pitch_deg);
  options.zoom = args.zoom;
  options.markers = !args.no_markers;
  if (!args.camera_pose.empty()) options.world_from_camera = ReadPullCamera(args.camera_pose);
  if (!args.capture.empty()) options.capture = args.capture;
  return options;
}

void Render(RenderArgs& args) {
  std::vector<std::filesystem::path> inputs = {args.scene.input};
  if (!args.scene.material_file.empty()) inputs.push_back(args.scene.material_file);
  if (!args.scene.parameters.empty()) inputs.push_back(args.scene.parameters);
  if (!args.capture.empty()) inputs.push_back(args.capture);
  RefuseToOverwriteInputs(args.output, inputs);
  if (!args.video.empty()) RefuseToOverwriteInputs(args.video, inputs);
  if (args.size[0] < 1 || args.size[1] < 1) {
    throw InputError("", "--size", "expected a positive WIDTH,HEIGHT");
  }
  const Tree tree = LoadTreeForViewing(args.scene);
  FinishSimulationArgs(tree, args.run);
  const viewer::SceneAssets assets =
      viewer::LoadSceneAssets(tree, args.scene.input, args.scene.foliage);
  const viewer::RenderResult result =
      viewer::RenderSimulation(tree, args.run.sim, assets.foliage_or_null(), assets.leaves,
                               RenderOptionsFromArgs(args), args.output);
  spdlog::info(
      "rendered {} frames of {}x{} to {} in {:.1f} s ({:.1f} ms a frame to draw, {} "
      "triangles) with {}",
      result.frames, result.width, result.height, args.output, result.seconds,
      result.draw_ms_per_frame, result.triangles_per_frame, result.backend);
  if (!args.video.empty()) {
    viewer::EncodeVideo(args.output, args.video, {.fps = result.simulated_fps});
    spdlog::info("wrote {} ({} frames at {} fps)", args.video, result.frames, result.simulated_fps);
  }
}

}  // namespace

void RegisterRender(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* verb = app.add_subcommand(
      "render",
      "Render a simulation run without a display (EGL, or Xvfb when that is what works) to PNG "
      "frames and a video; side by side with a capture's colour frames (paper Fig. 15)");
  AddRenderOptions(verb, *args);
  verb->callback([args] { Render(*args); });
}

}  // namespace simtree::cli
