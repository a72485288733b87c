#include "simtree/viewer/view.h"

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/core/interrupt.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/units.h"
#include "simtree/dynamics/live_pull.h"
#include "simtree/io/image_io.h"
#include "simtree/viewer/detail/camera.h"
#include "simtree/viewer/detail/gl.h"
#include "simtree/viewer/detail/gl_objects.h"
#include "simtree/viewer/detail/offscreen_context.h"
#include "simtree/viewer/detail/viewer_impl.h"

namespace simtree::viewer {
namespace {

double Seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

}  // namespace

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

void ViewerOptions::Validate() const {
  ValidateFramebuffer(width, height, samples, "viewer options");
  CheckOption(fps > 0.0 && std::isfinite(fps), "viewer options", "fps",
              fmt::format("expected a frame rate > 0, got {}", fps));
  scene.Validate();
  dynamics.Validate();
  if (pull) pull->Validate();
}

Viewer::Viewer(const Tree& tree, const SceneAssets& assets, const ViewerOptions& options)
    : impl_(std::make_unique<Impl>()) {
  options.Validate();
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

// One frame of simulated time: 1 / fps with a fixed step or a single step, else the frame's wall
// time (capped, so a slow frame does not jump the tree).
void Viewer::Impl::AdvanceSimulation(double wall_dt) {
  if (playing || step_once) {
    const double dt =
        options.fixed_step || step_once ? 1.0 / options.fps : std::clamp(wall_dt, 1e-4, 1.0 / 15.0);
    dynamics::AdvanceFrame(*sim, pull, dt);
    step_once = false;
  }
  if (options.measured) comparison = CompareMarkers(*options.measured, options.markers, *sim);
}

// The scene, its overlays and the panel, screenshots of the result, then the swap.
void Viewer::Impl::DrawFrame() {
  const CameraView view = SceneView();
  SceneStyle frame_style = style;
  frame_style.hovered_branch = hovered;
  frame_style.selected_branch = drag == Drag::kGrab ? selected : -1;
  scene->SetPose(*sim);
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window, &fw, &fh);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, fw, fh);
  scene->Draw(view, frame_style, ViewportX());
  DrawOverlays(view);
  DrawPanel();
  ImGui::Render();
  glViewport(0, 0, fw, fh);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  for (const std::string& path : pending_screenshots) Screenshot(path);
  pending_screenshots.clear();
  glfwSwapBuffers(window);
  stats.triangles = scene->triangle_count(frame_style.leaves);
}

void Viewer::Impl::CountFrame(double frame_s, double simulate_s, double draw_s, double wall_dt) {
  ++stats.frames;
  sum_frame += frame_s;
  sum_simulate += simulate_s;
  sum_draw += draw_s;
  stats.mean_frame_ms = 1000.0 * sum_frame / stats.frames;
  stats.mean_simulate_ms = 1000.0 * sum_simulate / stats.frames;
  stats.mean_draw_ms = 1000.0 * sum_draw / stats.frames;
  recent_frame_ms = 0.9 * recent_frame_ms + 0.1 * 1000.0 * wall_dt;
}

bool Viewer::Frame() {
  Impl& m = *impl_;
  // Ctrl-C in the terminal closes the window like its close button.
  if (m.quit || glfwWindowShouldClose(m.window) || InterruptRequested()) return false;
  const auto start = Clock::now();
  const double wall_dt = Seconds(m.last_frame, start);
  m.last_frame = start;
  glfwPollEvents();
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  // Input first (the script's or the user's), so the frame shows what it did.
  if (m.scripted()) {
    m.RunScript();
  } else {
    m.HandleRealInput();
  }
  if (m.drag == Drag::kNone) m.UpdateHover();
  const auto sim_start = Clock::now();
  m.AdvanceSimulation(wall_dt);
  const auto draw_start = Clock::now();
  m.DrawFrame();
  const auto end = Clock::now();
  m.CountFrame(Seconds(start, end), Seconds(sim_start, draw_start), Seconds(draw_start, end),
               wall_dt);
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
