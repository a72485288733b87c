#pragma once
// `simtree view`: the interactive window (GLFW, OpenGL 3.3 core, a Dear ImGui panel).
//
//  - Mouse: left-drag on a branch pulls it with a rope that follows the cursor (release lets go);
//    left-drag elsewhere orbits; right- or middle-drag (or shift + left) pans; the wheel zooms.
//    Hovering shows a branch's id, level, material and whether it was measured or interpolated.
//  - Keys: space play/pause, s step, r reset, l leaves, w wind, g grid, c colouring, h panel,
//    p or F12 screenshot, q or escape quit.
//  - Panel: simulation controls, pull, wind, the picked branch's (or its level's) frequency,
//    damping and stiffness live, display switches, playback against measured markers, screenshot.
//  - Scripted input (script.h) drives the same handlers, one simulation frame per drawn frame.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "simtree/core/tree.h"
#include "simtree/dynamics/simulate.h"
#include "simtree/io/trajectories.h"
#include "simtree/viewer/detail/script.h"
#include "simtree/viewer/scene_assets.h"
#include "simtree/viewer/scene_renderer.h"

namespace simtree::viewer {

struct ViewerOptions {
  int width = 1280;  // window size (pixels, 1 to 16384)
  int height = 800;
  // Multisample anti-aliasing samples of the window (0 to 16; costly on a software rasteriser).
  int samples = 0;
  bool vsync = false;             // wait for the display's refresh
  std::string title = "simtree";  // of the window
  // The style at the start (leaves, grid, colouring, background); the hovered and selected
  // branches follow the mouse.
  SceneStyle style;
  SceneOptions scene;                  // tubes, bark, grid spacing, leaf detail
  dynamics::DynamicsOptions dynamics;  // the model, as `simulate` takes it
  // A pull test played from t = 0 (and after every reset), as `simulate --pull` plays it.
  std::optional<dynamics::PullSchedule> pull;
  // Simulation time per frame: 1 / fps (scripted runs, benchmarks; the CLI sets it for scripts)
  // or the wall time of the frame (interactive, capped at 1/15 s).
  bool fixed_step = false;
  double fps = 30.0;  // simulated frames per second with fixed_step and for a single step (> 0)
  bool start_paused = false;  // the simulation waits for play (space)
  // Playback: measured markers (world frame) against the simulated `markers` of the same ids.
  std::optional<Trajectories> measured;
  std::vector<Marker> markers;       // drawn as dots; those on no branch of the tree are skipped
  std::vector<ScriptAction> script;  // scripted input (script.h), one action a frame or more
  std::string script_source;         // the script's file, for messages
  std::filesystem::path screenshot_dir = ".";  // where the p key and the panel's button write

  // Throws InputError ("viewer options", the field) for a value out of range, and as the
  // scene, dynamics and pull schedule's Validate() do.
  void Validate() const;
};

struct ViewerStats {
  int frames = 0;
  double mean_frame_ms = 0.0;  // wall time per frame, everything included
  double mean_draw_ms = 0.0;   // scene and panel drawing and the buffer swap
  double mean_simulate_ms = 0.0;
  int64_t triangles = 0;                 // per frame, as drawn last
  std::string renderer;                  // GL_RENDERER and version
  std::vector<std::string> screenshots;  // written, in order
};

class Viewer {
 public:
  // Opens the window. Throws InputError for options out of range (options.Validate()) and
  // simtree::Error when there is no display or no OpenGL 3.3.
  Viewer(const Tree& tree, const SceneAssets& assets, const ViewerOptions& options);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  // One frame: input (or the script), simulation, drawing, swap. False once the window should
  // close (the user closed it, pressed q, or the script said quit).
  bool Frame();
  // Frames until closed.
  void Run();

  const ViewerStats& stats() const;
  const dynamics::TreeDynamics& dynamics() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace simtree::viewer
