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

void RegisterRender(CLI::App& app) {
  struct Args {
    SceneArgs scene;
    SimulationArgs run;
    std::string output, video, capture, camera_pose, backend = "auto";
    std::vector<int> size = {1280, 720};
    int msaa = 4;
    double yaw_deg = -90.0, pitch_deg = 8.0, zoom = 1.0;
    bool no_markers = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "render",
      "Render a simulation run without a display (EGL, or Xvfb when that is what works) to PNG "
      "frames and a video; side by side with a capture's colour frames (paper Fig. 15)");
  AddTreeInput(verb, args->scene);
  verb->add_option("-o,--out", args->output,
                   "Frames folder: 000000.png, 000001.png, ... (replaced whole, or left "
                   "untouched on error)")
      ->required();
  verb->add_option("--video", args->video,
                   "Also encode the frames into this video (.mp4, H.264, through ffmpeg)");
  AddPullOptions(verb, args->run);
  AddRunOptions(verb, args->run);
  AddWindOptions(verb, args->run);
  AddModelOptions(verb, args->run);
  AddSceneOptions(verb, args->scene);

  auto* camera = verb->add_option_group("camera");
  camera->add_option("--size", args->size, "Frame size WIDTH,HEIGHT in pixels")
      ->expected(2)
      ->delimiter(',')
      ->capture_default_str();
  camera
      ->add_option("--yaw-deg", args->yaw_deg,
                   "Where the camera stands, degrees counter-clockwise from +X around the tree "
                   "(-90: in front, looking along +Y)")
      ->capture_default_str();
  camera->add_option("--pitch-deg", args->pitch_deg, "Camera height angle above the horizon")
      ->capture_default_str();
  camera->add_option("--zoom", args->zoom, "Distance factor (< 1 comes closer)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  camera->add_option("--msaa", args->msaa, "Anti-aliasing samples (0 = off)")
      ->capture_default_str()
      ->check(CLI::Range(0, 16));
  camera
      ->add_option("--side-by-side", args->capture,
                   "Capture folder: its pull-test colour frames on the left, the simulation "
                   "from the pull camera on the right, at the capture's frame times")
      ->check(CLI::ExistingDirectory);
  camera
      ->add_option("--camera-pose", args->camera_pose,
                   "Pose JSON of the camera (world_from_camera, as gt/pull_camera.json); "
                   "default for --side-by-side: <capture>/gt/pull_camera.json")
      ->check(CLI::ExistingFile);
  camera->add_flag("--no-markers", args->no_markers, "Do not draw the tree's markers");
  verb->add_option("--backend", args->backend,
                   "Headless OpenGL: auto (EGL, else Xvfb), egl or xvfb")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "egl", "xvfb"}));

  verb->footer(Examples({
      "simtree render tree02.txt --pull 20 --force 150 --release 2 --duration 6 --out frames/ "
      "--video pull.mp4",
      "simtree render tree.json --wind 8 --duration 10 --yaw-deg 0 --out windy/",
      "simtree render tree.json --pull 3 --force 80 --side-by-side capture/ --out fig15/ "
      "--video fig15.mp4",
  }));

  verb->callback([args] {
    Args& a = *args;
    std::vector<std::filesystem::path> inputs = {a.scene.input};
    if (!a.scene.material_file.empty()) inputs.push_back(a.scene.material_file);
    if (!a.scene.parameters.empty()) inputs.push_back(a.scene.parameters);
    if (!a.capture.empty()) inputs.push_back(a.capture);
    RefuseToOverwriteInputs(a.output, inputs);
    if (!a.video.empty()) RefuseToOverwriteInputs(a.video, inputs);
    if (a.size[0] < 1 || a.size[1] < 1) {
      throw InputError("", "--size", "expected a positive WIDTH,HEIGHT");
    }
    const Tree tree = LoadTreeForViewing(a.scene);
    FinishSimulationArgs(tree, a.run);
    const viewer::SceneAssets assets =
        viewer::LoadSceneAssets(tree, a.scene.input, a.scene.foliage);

    viewer::RenderOptions options;
    options.width = a.size[0];
    options.height = a.size[1];
    options.samples = a.msaa;
    options.backend = a.backend == "egl"    ? viewer::OffscreenBackend::kEgl
                      : a.backend == "xvfb" ? viewer::OffscreenBackend::kXvfb
                                            : viewer::OffscreenBackend::kAuto;
    options.style = StyleFromArgs(a.scene);
    options.yaw_rad = DegToRad(a.yaw_deg);
    options.pitch_rad = DegToRad(a.pitch_deg);
    options.zoom = a.zoom;
    options.markers = !a.no_markers;
    if (!a.camera_pose.empty()) options.world_from_camera = ReadPullCamera(a.camera_pose);
    if (!a.capture.empty()) options.capture = a.capture;
    const viewer::RenderResult result = viewer::RenderSimulation(
        tree, a.run.sim, assets.foliage_or_null(), assets.leaves, options, a.output);
    spdlog::info(
        "rendered {} frames of {}x{} to {} in {:.1f} s ({:.1f} ms a frame to draw, {} "
        "triangles) with {}",
        result.frames, result.width, result.height, a.output, result.seconds,
        result.draw_ms_per_frame, result.triangles_per_frame, result.backend);
    if (!a.video.empty()) {
      viewer::EncodeVideo(a.output, a.video, {.fps = result.simulated_fps});
      spdlog::info("wrote {} ({} frames at {} fps)", a.video, result.frames, result.simulated_fps);
    }
  });
}

}  // namespace simtree::cli
