#pragma once
// `simtree render`: a simulation run drawn frame by frame without a display (offscreen_context.h)
// into numbered PNGs, optionally encoded into a video. Two layouts:
//  - the tree alone, from an orbit camera that frames it (or a calibrated camera);
//  - side by side (the paper's Fig. 15): a capture's pull-test colour frames on the left and the
//    simulation drawn from the same camera (its intrinsics and pose) on the right, frame for frame
//    at the capture's times.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "simtree/core/tree.h"
#include "simtree/dynamics/simulate.h"
#include "simtree/viewer/detail/camera.h"
#include "simtree/viewer/detail/foliage.h"
#include "simtree/viewer/detail/leaf_model.h"
#include "simtree/viewer/detail/offscreen_context.h"
#include "simtree/viewer/scene_renderer.h"

namespace simtree::viewer {

struct RenderOptions {
  // Size of the simulated view (pixels, 1 to 16384); side by side takes the capture camera's.
  int width = 1280;
  int height = 720;
  int samples = 4;  // multisample anti-aliasing samples per pixel (0 = off, at most 16)
  OffscreenBackend backend = OffscreenBackend::kAuto;  // kAuto: EGL, else Xvfb
  SceneStyle style;                                    // leaves, grid, colouring, background
  SceneOptions scene;                                  // tubes, bark, grid spacing, leaf detail
  // Orbit camera angles about the tree's centre (rad); the distance frames the whole tree.
  double yaw_rad = -1.5707963267948966;
  double pitch_rad = 0.15;
  double zoom = 1.0;  // distance factor (> 0; < 1 comes closer)
  // A calibrated camera instead of the orbit camera (needs world_from_camera); side by side
  // takes the capture's pull camera instead.
  std::optional<CameraIntrinsics> intrinsics;
  // The camera's pose: for `intrinsics`, and for side by side (default: the capture's
  // gt/pull_camera.json).
  std::optional<Eigen::Isometry3d> world_from_camera;
  // Side by side with this capture's pull stream: the run's frame rate and duration become the
  // capture's, whatever the simulation options say.
  std::optional<std::filesystem::path> capture;
  bool markers = true;  // the tree's markers as dots

  // Throws InputError ("render options", the field) for a value out of range.
  void Validate() const;
};

struct RenderResult {
  int frames = 0;
  int width = 0, height = 0;  // of the written frames
  std::string backend;        // what drew them (EGL surfaceless, Xvfb ...)
  double seconds = 0.0;       // wall time, simulation and drawing and writing
  double draw_ms_per_frame = 0.0;
  int64_t triangles_per_frame = 0;
  double simulated_fps = 0.0;  // frames per simulated second
};

// Runs `simulation` on `tree` and writes <out_dir>/000000.png, 000001.png, ... (the folder is
// replaced whole, or left untouched on error). `foliage` may be null. For side by side the run's
// frame rate and duration become the capture's. Throws InputError before any work for options out
// of range, a capture without a pull stream or camera pose, and as RunSimulation does.
RenderResult RenderSimulation(const Tree& tree, dynamics::SimulationOptions simulation,
                              const LeafAssets* foliage, const std::vector<LeafInstance>& leaves,
                              const RenderOptions& options, const std::filesystem::path& out_dir);

}  // namespace simtree::viewer
