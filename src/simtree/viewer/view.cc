#include "simtree/viewer/view.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/core/units.h"
#include "simtree/dynamics/live_pull.h"
#include "simtree/io/image_io.h"
#include "simtree/viewer/detail/camera.h"
#include "simtree/viewer/detail/gl.h"
#include "simtree/viewer/detail/gl_objects.h"
#include "simtree/viewer/detail/material_edit.h"
#include "simtree/viewer/detail/picking.h"
#include "simtree/viewer/marker_playback.h"

namespace simtree::viewer {
namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// What the left button is doing.
enum class Drag { kNone, kOrbit, kPan, kGrab };

// How a grabbed branch is pulled: its point follows the cursor (a rope that displaces it
// statically to where the cursor is), or with a tension proportional to the drag.
enum class GrabMode { kFollow = 0, kForce = 1 };

std::string BranchDescription(const Tree& tree, const dynamics::TreeDynamics& sim, int id) {
  const Branch& b = tree.branches[id];
  const Material& m = sim.material(id);
  return fmt::format(
      "branch {} (level {}, parent {}): f {:.3g} Hz, damping {:.3g}, k {:.4g} N/m, "
      "{}",
      id, b.level, b.parent, m.modes[0].frequency_hz, m.modes[0].damping_ratio, m.stiffness,
      ToString(m.source));
}

}  // namespace

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
  float max_tension = 800.0f;  // N, the top of the demo's force slider
  int material_target = 0;     // 0: the selected branch, 1: its whole level

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

  void Open();
  void HandleRealInput();
  void RunScript();
  void DoAction(const ScriptAction& a);
  void Key(const std::string& name);
  void Press(double x, double y);
  void Move(double x, double y);
  void ReleaseButton();
  void UpdateHover();
  void PullTo(double x, double y);
  void Reset();
  void SetWind(bool on);
  void SetLeaves(bool on);
  void EditMaterial(MaterialProperty property, double value, const std::vector<int>& branches);
  std::vector<int> MaterialTargets() const;
  void DrawPanel();
  void DrawOverlays(const CameraView& view);
  void Screenshot(const std::string& path);
  std::string NextScreenshotPath() const;
};

void Viewer::Impl::Open() {
  glfwSetErrorCallback(
      [](int code, const char* message) { spdlog::debug("GLFW error {}: {}", code, message); });
  if (!glfwInit()) {
    throw Error(
        "view: cannot open a window: no X display (set DISPLAY, or run under xvfb-run; "
        "`simtree render` draws without one)");
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SAMPLES, options.samples);
  window = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
  if (window == nullptr) {
    glfwTerminate();
    throw Error("view: cannot create an OpenGL 3.3 core window on this display");
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(options.vsync ? 1 : 0);
  glfwSetWindowUserPointer(window, this);
  // Installed before ImGui's, which call them after their own.
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
    auto* self = static_cast<Impl*>(glfwGetWindowUserPointer(w));
    if (action != GLFW_PRESS || self->scripted() || ImGui::GetIO().WantCaptureKeyboard) return;
    const char* name = glfwGetKeyName(key, 0);
    if (key == GLFW_KEY_SPACE)
      self->Key("space");
    else if (key == GLFW_KEY_ESCAPE)
      self->Key("escape");
    else if (key == GLFW_KEY_F12)
      self->Key("f12");
    else if (key == GLFW_KEY_RIGHT)
      self->Key("s");
    else if (name != nullptr)
      self->Key(name);
  });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double dy) {
    auto* self = static_cast<Impl*>(glfwGetWindowUserPointer(w));
    if (self->scripted() || ImGui::GetIO().WantCaptureMouse) return;
    self->orbit.Zoom(std::pow(0.9, dy));
  });
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini beside the user's files
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 330 core");
  imgui_ready = true;
  stats.renderer = gl::RendererName();
}

void Viewer::Impl::Reset() {
  sim->Reset();
  pull.Restart();
  grab_rope = -1;
  if (drag == Drag::kGrab) drag = Drag::kNone;
}

void Viewer::Impl::SetWind(bool on) {
  dynamics::WindOptions wind = sim->wind();
  wind.enabled = on;
  wind.mean_speed_mps = wind_speed;
  const double heading = DegToRad(wind_heading_deg);
  wind.direction = {std::cos(heading), std::sin(heading), 0.0};
  sim->SetWind(wind);
}

void Viewer::Impl::SetLeaves(bool on) { style.leaves = on && scene->has_leaves(); }

std::vector<int> Viewer::Impl::MaterialTargets() const {
  if (selected < 0) return {};
  if (material_target == 1) return BranchesOfLevel(tree, tree.branches[selected].level);
  return {selected};
}

void Viewer::Impl::EditMaterial(MaterialProperty property, double value,
                                const std::vector<int>& branches) {
  const int n = EditMaterials(*sim, branches, property, value);
  spdlog::info("view: {} = {} on {} branch{}", ToString(property), value, n, n == 1 ? "" : "es");
}

void Viewer::Impl::Key(const std::string& name) {
  if (name == "space") {
    playing = !playing;
  } else if (name == "s") {
    playing = false;
    step_once = true;
  } else if (name == "r") {
    Reset();
  } else if (name == "l") {
    SetLeaves(!style.leaves);
  } else if (name == "w") {
    SetWind(!sim->wind().enabled);
  } else if (name == "g") {
    style.grid = !style.grid;
  } else if (name == "c") {
    style.colouring = static_cast<BranchColouring>((static_cast<int>(style.colouring) + 1) % 3);
  } else if (name == "h") {
    panel = !panel;
  } else if (name == "p" || name == "f12") {
    pending_screenshots.push_back(NextScreenshotPath());
  } else if (name == "q" || name == "escape") {
    quit = true;
  } else {
    spdlog::debug("view: key {} does nothing", name);
  }
}

void Viewer::Impl::Press(double x, double y) {
  mouse_x = x;
  mouse_y = y;
  left_down = true;
  if (x < ViewportX()) return;  // on the panel
  if (shift) {
    drag = Drag::kPan;
    return;
  }
  const CameraView view = SceneView();
  const Ray ray = view.PixelRay(x - ViewportX(), y);
  const auto hit = PickBranch(tree, sim->node_positions(), view, ray);
  if (!hit) {
    drag = Drag::kOrbit;
    return;
  }
  drag = Drag::kGrab;
  selected = hit->branch;
  grab_arc = hit->arc_length;
  grab_plane_point = hit->point;
  grab_plane_normal = view.Forward();
  grab_target = hit->point;
  spdlog::info("view: grabbed {} at {:.3f} m", BranchDescription(tree, *sim, selected), grab_arc);
}

void Viewer::Impl::PullTo(double x, double y) {
  const CameraView view = SceneView();
  const Ray ray = view.PixelRay(x - ViewportX(), y);
  const double denom = ray.direction.dot(grab_plane_normal);
  if (std::abs(denom) < 1e-9) return;
  const double t = (grab_plane_point - ray.origin).dot(grab_plane_normal) / denom;
  if (t <= 0.0) return;
  grab_target = ray.origin + t * ray.direction;
  const Eigen::Vector3d rest = tree.branches[selected].PointAt(grab_arc);
  const Eigen::Vector3d pull_vector = grab_target - rest;
  const double distance = pull_vector.norm();
  // Anchored beyond the cursor, so the rope's direction holds as the point comes near it.
  const Eigen::Vector3d direction =
      distance > 1e-9 ? Eigen::Vector3d(pull_vector / distance) : grab_plane_normal;
  dynamics::Rope rope;
  rope.branch = selected;
  rope.arc_length = grab_arc;
  rope.anchor = grab_target + 2.0 * direction;
  if (grab_mode == GrabMode::kFollow) {
    // The tension that moves the point statically to the cursor: the compliance along the pull
    // from a small probe (the model is linear), capped like the demo's force slider, since a
    // branch cannot stretch along its own axis.
    dynamics::Rope probe = rope;
    probe.mode = dynamics::Rope::Mode::kDisplacement;
    probe.displacement_m = 0.01;
    probe.anchor = sim->PointPosition(selected, grab_arc) + 2.0 * direction;
    double tension = 0.0;
    try {
      const int id = sim->AttachRope(probe);
      tension = sim->RopeTension(id) * distance / probe.displacement_m;
      sim->ReleaseRope(id);
    } catch (const InputError&) {
      tension = max_tension;  // the point cannot move that way: pull as hard as allowed
    }
    rope.force_n = std::min(tension, static_cast<double>(max_tension));
  } else {
    rope.force_n = std::min(force_per_metre * distance, static_cast<double>(max_tension));
  }
  if (grab_rope >= 0 && sim->HasRope(grab_rope)) {
    sim->UpdateRope(grab_rope, rope);
  } else {
    grab_rope = sim->AttachRope(rope);
  }
}

void Viewer::Impl::Move(double x, double y) {
  const double dx = x - mouse_x, dy = y - mouse_y;
  mouse_x = x;
  mouse_y = y;
  if (!left_down) return;
  switch (drag) {
    case Drag::kOrbit:
      orbit.Orbit(-0.006 * dx, 0.006 * dy);
      break;
    case Drag::kPan:
      orbit.Pan(dx, dy, SceneView().height);
      break;
    case Drag::kGrab:
      PullTo(x, y);
      break;
    case Drag::kNone:
      break;
  }
}

void Viewer::Impl::ReleaseButton() {
  left_down = false;
  if (drag == Drag::kGrab && grab_rope >= 0) {
    if (sim->HasRope(grab_rope)) {
      spdlog::info("view: released branch {} (tension was {:.1f} N)", selected,
                   sim->RopeTension(grab_rope));
      sim->ReleaseRope(grab_rope);
    }
    grab_rope = -1;
  }
  drag = Drag::kNone;
}

void Viewer::Impl::UpdateHover() {
  hovered = -1;
  if (mouse_x < ViewportX()) return;
  const CameraView view = SceneView();
  if (mouse_x - ViewportX() >= view.width || mouse_y < 0 || mouse_y >= view.height) return;
  const auto hit =
      PickBranch(tree, sim->node_positions(), view, view.PixelRay(mouse_x - ViewportX(), mouse_y));
  if (hit) hovered = hit->branch;
}

void Viewer::Impl::HandleRealInput() {
  const ImGuiIO& io = ImGui::GetIO();
  double x = 0, y = 0;
  glfwGetCursorPos(window, &x, &y);
  int ww = 1, wh = 1, fw = 1, fh = 1;
  glfwGetWindowSize(window, &ww, &wh);
  glfwGetFramebufferSize(window, &fw, &fh);
  x *= static_cast<double>(fw) / std::max(ww, 1);
  y *= static_cast<double>(fh) / std::max(wh, 1);
  shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
          glfwGetKey(window, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
  const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  const bool other = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                     glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
  if (left && !left_down && !io.WantCaptureMouse) {
    Press(x, y);
  } else if (other && !left_down && !io.WantCaptureMouse) {
    mouse_x = x;
    mouse_y = y;
    left_down = true;
    drag = Drag::kPan;
  } else if (!left && !other && left_down) {
    ReleaseButton();
  } else {
    Move(x, y);
  }
  mouse_x = x;
  mouse_y = y;
}

void Viewer::Impl::DoAction(const ScriptAction& a) {
  switch (a.verb) {
    case ScriptVerb::kPick:
      mouse_x = a.numbers[0];
      mouse_y = a.numbers[1];
      Press(a.numbers[0], a.numbers[1]);
      if (drag != Drag::kGrab) {
        spdlog::warn("{}: line {}: pick: no branch at ({}, {})", options.script_source, a.line,
                     a.numbers[0], a.numbers[1]);
      }
      break;
    case ScriptVerb::kPickBranch: {
      if (a.branch >= tree.size()) {
        throw InputError(options.script_source, fmt::format("line {}", a.line),
                         fmt::format("pick-branch: expected a branch id in [0, {}], got {}",
                                     tree.size() - 1, a.branch));
      }
      const double length = tree.branches[a.branch].Length();
      const double s = a.arc_length < 0.0 ? length : std::min(a.arc_length, length);
      const auto pixel = SceneView().Project(sim->PointPosition(a.branch, s));
      if (!pixel) {
        spdlog::warn("{}: line {}: pick-branch: branch {} is behind the camera",
                     options.script_source, a.line, a.branch);
        break;
      }
      mouse_x = pixel->x() + ViewportX();
      mouse_y = pixel->y();
      spdlog::info("view: pick-branch {} at pixel ({:.0f}, {:.0f})", a.branch, mouse_x, mouse_y);
      Press(mouse_x, mouse_y);
      break;
    }
    case ScriptVerb::kDrag:
    case ScriptVerb::kDragBy:
      drag_to_x = a.numbers[0] + (a.verb == ScriptVerb::kDragBy ? mouse_x : 0.0);
      drag_to_y = a.numbers[1] + (a.verb == ScriptVerb::kDragBy ? mouse_y : 0.0);
      drag_frames_left = static_cast<int>(a.numbers[2]);
      break;
    case ScriptVerb::kRelease:
      ReleaseButton();
      break;
    case ScriptVerb::kHover:
      Move(a.numbers[0], a.numbers[1]);
      UpdateHover();
      if (hovered >= 0) {
        spdlog::info("view: hover ({}, {}): {}", a.numbers[0], a.numbers[1],
                     BranchDescription(tree, *sim, hovered));
      } else {
        spdlog::info("view: hover ({}, {}): nothing", a.numbers[0], a.numbers[1]);
      }
      break;
    case ScriptVerb::kWait:
      script_wait = static_cast<int>(a.numbers[0]);
      break;
    case ScriptVerb::kScreenshot:
      pending_screenshots.push_back(a.text);
      break;
    case ScriptVerb::kKey:
      Key(a.text);
      break;
    case ScriptVerb::kPlay:
      playing = true;
      break;
    case ScriptVerb::kPause:
      playing = false;
      break;
    case ScriptVerb::kStep:
      playing = false;
      step_once = true;
      break;
    case ScriptVerb::kReset:
      Reset();
      break;
    case ScriptVerb::kWind:
      if (!a.numbers.empty()) {
        wind_speed = static_cast<float>(a.numbers[0]);
        SetWind(wind_speed > 0.0f);
      } else {
        SetWind(a.text == "on");
      }
      break;
    case ScriptVerb::kLeaves:
      SetLeaves(a.text == "on");
      break;
    case ScriptVerb::kMaterial: {
      const bool level = a.text.rfind("level", 0) == 0;
      const MaterialProperty property =
          ParseMaterialProperty(a.text.substr(a.text.find(' ') + 1), "material");
      if (!level && a.branch >= tree.size()) {
        throw InputError(options.script_source, fmt::format("line {}", a.line),
                         fmt::format("material: expected a branch id in [0, {}], got {}",
                                     tree.size() - 1, a.branch));
      }
      EditMaterial(property, a.numbers[0],
                   level ? BranchesOfLevel(tree, a.branch) : std::vector<int>{a.branch});
      break;
    }
    case ScriptVerb::kOrbit:
      orbit.Orbit(DegToRad(a.numbers[0]), DegToRad(a.numbers[1]));
      break;
    case ScriptVerb::kZoom:
      orbit.Zoom(a.numbers[0]);
      break;
    case ScriptVerb::kQuit:
      quit = true;
      break;
  }
}

void Viewer::Impl::RunScript() {
  // A drag in progress moves the mouse a step per frame; a wait holds the script.
  if (drag_frames_left > 0) {
    const double f = 1.0 / drag_frames_left;
    Move(mouse_x + f * (drag_to_x - mouse_x), mouse_y + f * (drag_to_y - mouse_y));
    --drag_frames_left;
    return;
  }
  if (script_wait > 0) {
    --script_wait;
    return;
  }
  // Everything up to the next action that takes frames (or a screenshot, taken this frame).
  while (script_next < options.script.size() && !quit) {
    const ScriptAction& a = options.script[script_next++];
    DoAction(a);
    if (a.verb == ScriptVerb::kWait && script_wait > 0) {
      --script_wait;
      return;
    }
    if (a.verb == ScriptVerb::kDrag || a.verb == ScriptVerb::kDragBy) {
      RunScript();
      return;
    }
    if (a.verb == ScriptVerb::kScreenshot) return;
  }
}

std::string Viewer::Impl::NextScreenshotPath() const {
  for (int i = 1;; ++i) {
    const std::filesystem::path p = options.screenshot_dir / fmt::format("simtree-{:04d}.png", i);
    if (!std::filesystem::exists(p) &&
        std::find(pending_screenshots.begin(), pending_screenshots.end(), p.string()) ==
            pending_screenshots.end()) {
      return p.string();
    }
  }
}

void Viewer::Impl::Screenshot(const std::string& path) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window, &w, &h);
  glReadBuffer(GL_BACK);
  const RgbImage image = ReadPixels(w, h);
  const std::filesystem::path p(path);
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  WritePng(image, p);
  stats.screenshots.push_back(path);
  spdlog::info("view: screenshot {} ({}x{}, t = {:.3f} s)", path, w, h, sim->time());
}

void Viewer::Impl::DrawOverlays(const CameraView& view) {
  std::vector<Eigen::Vector3f> points, lines;
  if (grab_rope >= 0 && sim->HasRope(grab_rope)) {
    const Eigen::Vector3f p = sim->RopePoint(grab_rope).cast<float>();
    lines = {p, grab_target.cast<float>()};
    scene->DrawLines(view, lines, Eigen::Vector4f(0.95f, 0.85f, 0.2f, 1.0f));
    points = {grab_target.cast<float>()};
    scene->DrawPoints(view, points, Eigen::Vector4f(0.95f, 0.85f, 0.2f, 1.0f), 9.0f);
  }
  if (pull.rope_id() >= 0 && sim->HasRope(pull.rope_id())) {
    lines = {sim->RopePoint(pull.rope_id()).cast<float>(),
             sim->rope(pull.rope_id()).anchor.cast<float>()};
    scene->DrawLines(view, lines, Eigen::Vector4f(0.9f, 0.9f, 0.9f, 1.0f));
  }
  if (!show_markers) return;
  points.clear();
  for (const Marker& m : options.markers) {
    if (m.branch >= 0 && m.branch < tree.size()) {
      points.push_back(sim->PointPosition(m.branch, m.arc_length).cast<float>());
    }
  }
  scene->DrawPoints(view, points, Eigen::Vector4f(0.15f, 0.35f, 1.0f, 1.0f), 8.0f);
  if (comparison) {
    points.clear();
    lines.clear();
    for (const MarkerError& e : comparison->markers) {
      points.push_back(e.measured.cast<float>());
      lines.push_back(e.measured.cast<float>());
      lines.push_back(e.simulated.cast<float>());
    }
    scene->DrawLines(view, lines, Eigen::Vector4f(1.0f, 1.0f, 1.0f, 1.0f));
    scene->DrawPoints(view, points, Eigen::Vector4f(0.95f, 0.1f, 0.1f, 1.0f), 8.0f);
  }
}

void Viewer::Impl::DrawPanel() {
  const ImGuiIO& io = ImGui::GetIO();
  if (panel) {
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(panel_width, io.DisplaySize.y));
    ImGui::Begin("simtree", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::Text("%s", tree.metadata.source.empty() ? "tree" : tree.metadata.source.c_str());
    ImGui::Text("%d branches, %d nodes, %d leaves", tree.size(), tree.NodeCount(),
                scene->leaf_count());
    ImGui::Text("%.1f ms a frame (%.0f fps), %lld triangles", recent_frame_ms,
                recent_frame_ms > 0 ? 1000.0 / recent_frame_ms : 0.0,
                static_cast<long long>(stats.triangles));
    if (ImGui::CollapsingHeader("Simulation", ImGuiTreeNodeFlags_DefaultOpen)) {
      if (ImGui::Button(playing ? "Pause" : "Play")) playing = !playing;
      ImGui::SameLine();
      if (ImGui::Button("Step")) {
        playing = false;
        step_once = true;
      }
      ImGui::SameLine();
      if (ImGui::Button("Reset")) Reset();
      ImGui::Text("t = %.2f s, energy %.3g J", sim->time(), sim->Energy());
    }
    if (ImGui::CollapsingHeader("Pull", ImGuiTreeNodeFlags_DefaultOpen)) {
      int mode = static_cast<int>(grab_mode);
      ImGui::RadioButton("follow the cursor", &mode, 0);
      ImGui::SameLine();
      ImGui::RadioButton("force", &mode, 1);
      grab_mode = static_cast<GrabMode>(mode);
      if (grab_mode == GrabMode::kForce) {
        ImGui::SliderFloat("N per m", &force_per_metre, 1.0f, 2000.0f, "%.0f",
                           ImGuiSliderFlags_Logarithmic);
      }
      ImGui::SliderFloat("max N", &max_tension, 1.0f, 800.0f, "%.0f", ImGuiSliderFlags_Logarithmic);
      if (grab_rope >= 0 && sim->HasRope(grab_rope)) {
        ImGui::Text("rope on branch %d: %.1f N", selected, sim->RopeTension(grab_rope));
      } else {
        ImGui::TextDisabled("drag a branch to pull it");
      }
      if (ImGui::Button("Release all")) {
        sim->ReleaseAllRopes();
        grab_rope = -1;
      }
    }
    if (ImGui::CollapsingHeader("Wind", ImGuiTreeNodeFlags_DefaultOpen)) {
      bool on = sim->wind().enabled;
      bool changed = ImGui::Checkbox("wind", &on);
      changed |= ImGui::SliderFloat("m/s", &wind_speed, 0.0f, 20.0f, "%.1f");
      changed |= ImGui::SliderFloat("heading", &wind_heading_deg, -180.0f, 180.0f, "%.0f deg");
      if (changed) SetWind(on);
    }
    if (ImGui::CollapsingHeader("Material", ImGuiTreeNodeFlags_DefaultOpen)) {
      if (selected < 0) {
        ImGui::TextDisabled("pick a branch to tune it");
      } else {
        const Branch& b = tree.branches[selected];
        const Material& m = sim->material(selected);
        ImGui::Text("branch %d, level %d, %s", selected, b.level, ToString(m.source));
        ImGui::RadioButton("this branch", &material_target, 0);
        ImGui::SameLine();
        ImGui::RadioButton("its level", &material_target, 1);
        for (const MaterialProperty p : {MaterialProperty::kFrequency, MaterialProperty::kDamping,
                                         MaterialProperty::kStiffness}) {
          const PropertyRange range = RangeOf(p);
          float value = static_cast<float>(PropertyValue(m, p));
          const char* label = p == MaterialProperty::kFrequency ? "f (Hz)"
                              : p == MaterialProperty::kDamping ? "damping"
                                                                : "k (N/m)";
          if (ImGui::SliderFloat(label, &value, static_cast<float>(range.min),
                                 static_cast<float>(range.max), "%.4g",
                                 ImGuiSliderFlags_Logarithmic)) {
            EditMaterial(p, value, MaterialTargets());
          }
        }
      }
    }
    if (ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) {
      bool leaves = style.leaves;
      if (!scene->has_leaves()) {
        ImGui::TextDisabled("no leaves");
        if (!leaf_error.empty()) ImGui::TextWrapped("%s", leaf_error.c_str());
      } else if (ImGui::Checkbox("leaves", &leaves)) {
        SetLeaves(leaves);
      }
      ImGui::Checkbox("grid", &style.grid);
      ImGui::SameLine();
      ImGui::Checkbox("markers", &show_markers);
      int colouring = static_cast<int>(style.colouring);
      if (ImGui::Combo("colour", &colouring, "bark\0level\0material source\0")) {
        style.colouring = static_cast<BranchColouring>(colouring);
      }
    }
    if (options.measured && ImGui::CollapsingHeader("Playback", ImGuiTreeNodeFlags_DefaultOpen)) {
      if (comparison && !comparison->markers.empty()) {
        ImGui::Text("%zu markers: RMS %.1f mm, max %.1f mm", comparison->markers.size(),
                    1000.0 * comparison->rms_error_m, 1000.0 * comparison->max_error_m);
        for (size_t i = 0; i < comparison->markers.size() && i < 16; ++i) {
          const MarkerError& e = comparison->markers[i];
          ImGui::Text("%-8s %7.1f mm", e.label.c_str(), 1000.0 * e.error_m);
        }
      } else {
        ImGui::TextDisabled("no measured marker at t = %.2f s", sim->time());
      }
      ImGui::TextDisabled("red: measured, blue: simulated");
    }
    if (ImGui::Button("Screenshot")) pending_screenshots.push_back(NextScreenshotPath());
    ImGui::SameLine();
    ImGui::TextDisabled("(p)");
    ImGui::End();
  }
  if (hovered >= 0 && drag == Drag::kNone && !io.WantCaptureMouse) {
    const Material& m = sim->material(hovered);
    const Branch& b = tree.branches[hovered];
    ImGui::BeginTooltip();
    ImGui::Text("branch %d, level %d", hovered, b.level);
    ImGui::Text("f %.3g Hz, damping %.3g, k %.4g N/m", m.modes[0].frequency_hz,
                m.modes[0].damping_ratio, m.stiffness);
    ImGui::Text("%s", m.source == MaterialSource::kMeasured       ? "measured"
                      : m.source == MaterialSource::kInterpolated ? "interpolated"
                                                                  : "default (not measured)");
    ImGui::EndTooltip();
  }
}

Viewer::Viewer(const Tree& tree, const SceneAssets& assets, const ViewerOptions& options)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.options = options;
  m.tree = tree;
  m.style = options.style;
  m.leaf_error = assets.error;
  m.playing = !options.start_paused;
  m.sim = std::make_unique<dynamics::TreeDynamics>(tree, options.dynamics);
  m.wind_speed = static_cast<float>(options.dynamics.wind.mean_speed_mps);
  if (options.pull) m.pull = dynamics::LivePull(*m.sim, *options.pull);
  m.Open();
  m.scene =
      std::make_unique<SceneRenderer>(tree, assets.foliage_or_null(), assets.leaves, options.scene);
  m.style.leaves = m.style.leaves && m.scene->has_leaves();
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  const CameraView view = m.SceneView();
  m.orbit.Frame(lo, hi, static_cast<double>(view.width) / view.height);
  spdlog::info("view: {} ({} branches, {} nodes, {} leaves, {} triangles with leaves)",
               m.stats.renderer, tree.size(), tree.NodeCount(), m.scene->leaf_count(),
               m.scene->triangle_count(true));
  m.last_frame = Clock::now();
}

Viewer::~Viewer() {
  Impl& m = *impl_;
  m.scene.reset();
  if (m.imgui_ready) {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  if (m.window != nullptr) {
    glfwDestroyWindow(m.window);
    glfwTerminate();
  }
}

bool Viewer::Frame() {
  Impl& m = *impl_;
  if (m.quit || glfwWindowShouldClose(m.window)) return false;
  const auto start = Clock::now();
  const double wall_dt = Seconds(m.last_frame, start);
  m.last_frame = start;
  glfwPollEvents();

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  if (m.scripted()) {
    m.RunScript();
  } else {
    m.HandleRealInput();
  }
  if (m.drag == Drag::kNone) m.UpdateHover();

  // Simulation.
  const auto sim_start = Clock::now();
  if (m.playing || m.step_once) {
    const double dt = m.options.fixed_step || m.step_once ? 1.0 / m.options.fps
                                                          : std::clamp(wall_dt, 1e-4, 1.0 / 15.0);
    dynamics::AdvanceFrame(*m.sim, m.pull, dt);
    m.step_once = false;
  }
  if (m.options.measured) {
    m.comparison = CompareMarkers(*m.options.measured, m.options.markers, *m.sim);
  }
  const auto draw_start = Clock::now();

  // Drawing.
  const CameraView view = m.SceneView();
  SceneStyle style = m.style;
  style.hovered_branch = m.hovered;
  style.selected_branch = m.drag == Drag::kGrab ? m.selected : -1;
  m.scene->SetPose(*m.sim);
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(m.window, &fw, &fh);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, fw, fh);
  m.scene->Draw(view, style, m.ViewportX());
  m.DrawOverlays(view);
  m.DrawPanel();
  ImGui::Render();
  glViewport(0, 0, fw, fh);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  for (const std::string& path : m.pending_screenshots) m.Screenshot(path);
  m.pending_screenshots.clear();
  glfwSwapBuffers(m.window);
  const auto end = Clock::now();

  m.stats.triangles = m.scene->triangle_count(style.leaves);
  ++m.stats.frames;
  m.sum_frame += Seconds(start, end);
  m.sum_simulate += Seconds(sim_start, draw_start);
  m.sum_draw += Seconds(draw_start, end);
  m.stats.mean_frame_ms = 1000.0 * m.sum_frame / m.stats.frames;
  m.stats.mean_simulate_ms = 1000.0 * m.sum_simulate / m.stats.frames;
  m.stats.mean_draw_ms = 1000.0 * m.sum_draw / m.stats.frames;
  m.recent_frame_ms = 0.9 * m.recent_frame_ms + 0.1 * 1000.0 * wall_dt;
  if (m.scripted() && m.script_next >= m.options.script.size() && m.script_wait == 0 &&
      m.drag_frames_left == 0 && !m.quit) {
    // The script is done: the window stays for the user.
    m.options.script.clear();
  }
  return !m.quit;
}

void Viewer::Run() {
  while (Frame()) {
  }
}

const ViewerStats& Viewer::stats() const { return impl_->stats; }
const dynamics::TreeDynamics& Viewer::dynamics() const { return *impl_->sim; }

}  // namespace simtree::viewer
