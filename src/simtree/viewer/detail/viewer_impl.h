#pragma once
// The state of the interactive window (view.h's Viewer), shared by the files that handle it by
// concept: view.cc (window, frame, screenshots, overlays), viewer_input.cc (mouse and keys),
// viewer_script.cc (scripted input) and viewer_panel.cc (the side panel).

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "simtree/dynamics/live_pull.h"
#include "simtree/viewer/detail/camera.h"
#include "simtree/viewer/detail/material_edit.h"
#include "simtree/viewer/marker_playback.h"
#include "simtree/viewer/view.h"

namespace simtree::viewer {

using Clock = std::chrono::steady_clock;

// What the left button is doing.
enum class Drag { kNone, kOrbit, kPan, kGrab };

// How a grabbed branch is pulled: its point follows the cursor (a rope that displaces it
// statically to where the cursor is), or with a tension proportional to the drag.
enum class GrabMode { kFollow = 0, kForce = 1 };

// "branch 3 (level 1, parent 0): f 1.6 Hz, damping 0.02, k 5000 N/m, measured".
std::string BranchDescription(const Tree& tree, const dynamics::TreeDynamics& sim, int id);

struct Viewer::Impl {
  ViewerOptions options;
  Tree tree;
  GLFWwindow* window = nullptr;
  bool imgui_ready = false;
  std::unique_ptr<dynamics::TreeDynamics> sim;
  dynamics::LivePull pull;
  std::unique_ptr<SceneRenderer> scene;
  std::string leaf_error;
  OrbitCamera orbit;
  SceneStyle style;
  ViewerStats stats;

  // Controls.
  bool playing = true;
  bool step_once = false;
  bool quit = false;
  bool panel = true;
  bool show_markers = true;
  float panel_width = 340.0f;
  float wind_speed = 5.0f;
  float wind_heading_deg = 0.0f;
  GrabMode grab_mode = GrabMode::kFollow;
  float force_per_metre = 400.0f;
  float max_tension = 800.0f;                             // N, the top of the demo's force slider
  MaterialScope material_scope = MaterialScope::kBranch;  // what a panel edit changes

  // Mouse, in window pixels (continuous, top-left origin).
  double mouse_x = 0, mouse_y = 0;
  bool left_down = false;
  bool shift = false;
  Drag drag = Drag::kNone;
  int hovered = -1;
  int selected = -1;
  double grab_arc = 0.0;
  Eigen::Vector3d grab_plane_point = Eigen::Vector3d::Zero();
  Eigen::Vector3d grab_plane_normal = Eigen::Vector3d::UnitY();
  Eigen::Vector3d grab_target = Eigen::Vector3d::Zero();
  int grab_rope = -1;

  // Script.
  size_t script_next = 0;
  int script_wait = 0;
  int drag_frames_left = 0;
  double drag_to_x = 0, drag_to_y = 0;
  std::vector<std::string> pending_screenshots;

  // Timing.
  Clock::time_point last_frame = Clock::now();
  double sum_frame = 0, sum_draw = 0, sum_simulate = 0;
  double recent_frame_ms = 0;

  std::optional<MarkerComparison> comparison;

  bool scripted() const { return !options.script.empty(); }
  int ViewportX() const { return panel ? static_cast<int>(panel_width) : 0; }
  CameraView SceneView() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window, &w, &h);
    return orbit.View(std::max(1, w - ViewportX()), std::max(1, h));
  }

  // view.cc: the window, the frame, screenshots and overlays.
  void Open();
  void AdvanceSimulation(double wall_dt);
  void DrawFrame();
  void CountFrame(double frame_s, double simulate_s, double draw_s, double wall_dt);
  void Reset();
  void SetWind(bool on);
  void SetLeaves(bool on);
  void DrawOverlays(const CameraView& view);
  void Screenshot(const std::string& path);
  std::string NextScreenshotPath() const;
  // viewer_input.cc: mouse and keys.
  void HandleRealInput();
  void Key(const std::string& name);
  void Press(double x, double y);
  void Move(double x, double y);
  void ReleaseButton();
  void UpdateHover();
  void PullTo(double x, double y);
  void EditMaterial(MaterialProperty property, double value, const std::vector<int>& branches);
  std::vector<int> MaterialTargets() const;
  // viewer_script.cc: scripted input driving the same handlers.
  void RunScript();
  void DoAction(const ScriptAction& a);
  // viewer_panel.cc: the side panel and the hover tooltip.
  void DrawPanel();
  void DrawSimulationSection();
  void DrawPullSection();
  void DrawWindSection();
  void DrawMaterialSection();
  void DrawDisplaySection();
  void DrawPlaybackSection();
  void DrawHoverTooltip();
};

}  // namespace simtree::viewer
