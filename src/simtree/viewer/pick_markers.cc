#include "simtree/viewer/pick_markers.h"

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/core/interrupt.h"
#include "simtree/core/option_checks.h"
#include "simtree/io/capture.h"
#include "simtree/io/image_io.h"
#include "simtree/viewer/detail/gl.h"
#include "simtree/viewer/detail/pick_session.h"

#define GLFW_INCLUDE_NONE  // the GL declarations are gl.h's
#include <GLFW/glfw3.h>

namespace fs = std::filesystem;

namespace simtree::viewer {
namespace {

using detail::ImageView;
using detail::PickAction;
using detail::PickSession;
using detail::PickVerb;

// What is picked on: the stream's first colour frame and the markers to click.
struct PickInput {
  RgbImage image;
  int frame = 0;
  std::vector<MarkerLink> markers;
};

PickInput ReadPickInput(const fs::path& pull_dir) {
  if (!fs::is_regular_file(pull_dir / "markers.json")) {
    throw InputError((pull_dir / "markers.json").string(), "",
                     "missing: --pick asks for each marker of markers.json (simtree.markers, "
                     "docs/formats.md)");
  }
  PickInput in;
  in.markers = ReadMarkersJson(pull_dir / "markers.json");
  const std::vector<PullFrame> frames = ReadFramesCsv(pull_dir / "frames.csv");
  if (frames.empty()) {
    throw InputError((pull_dir / "frames.csv").string(), "", "expected at least one frame");
  }
  in.frame = frames[0].frame;
  in.image = ReadColorImage(pull_dir / frames[0].color);
  return in;
}

class PickWindow {
 public:
  PickWindow(const PickInput& input, const MarkerPickOptions& options)
      : session_(input.markers, input.image.width, input.image.height), options_(options) {
    const double fit = std::min(static_cast<double>(options.max_width) / input.image.width,
                                static_cast<double>(options.max_height) / input.image.height);
    width_ = std::max(320, static_cast<int>(std::lround(input.image.width * fit)));
    height_ = std::max(240, static_cast<int>(std::lround(input.image.height * fit)));
    Open();
    Upload(input.image);
    image_w_ = input.image.width;
    image_h_ = input.image.height;
    view_ = ImageView::Fit(image_w_, image_h_, width_, height_);
  }
  ~PickWindow() {
    if (texture_ != 0) glDeleteTextures(1, &texture_);
    if (imgui_ready_) {
      ImGui_ImplOpenGL3_Shutdown();
      ImGui_ImplGlfw_Shutdown();
      ImGui::DestroyContext();
    }
    if (window_ != nullptr) glfwDestroyWindow(window_);
    glfwTerminate();
  }
  PickWindow(const PickWindow&) = delete;
  PickWindow& operator=(const PickWindow&) = delete;

  // One frame: input (the script's or the user's), drawing, swap. False once finished or
  // cancelled.
  bool Frame() {
    if (glfwWindowShouldClose(window_) || InterruptRequested()) cancelled_ = true;  // as Escape
    if (finished_ || cancelled_) return false;
    glfwPollEvents();
    if (Scripted()) RunScript();
    Draw();
    ++frames_;
    return !(finished_ || cancelled_);
  }

  bool finished() const { return finished_; }
  int frames() const { return frames_; }
  const PickSession& session() const { return session_; }

 private:
  void Open() {
    glfwSetErrorCallback(
        [](int code, const char* message) { spdlog::debug("GLFW error {}: {}", code, message); });
    // DISPLAY unset refuses at once; otherwise GLFW's own connection decides (it also reaches
    // servers whose /tmp/.X11-unix socket file is gone, which HasDisplay() does not).
    const char* display = std::getenv("DISPLAY");
    if (display == nullptr || display[0] == '\0' || !glfwInit()) {
      throw Error(
          "track --pick: cannot open a window: no X display (set DISPLAY, or run under "
          "xvfb-run); without one give the first-frame pixels with --init or --init-from");
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window_ = glfwCreateWindow(width_, height_, "simtree track --pick", nullptr, nullptr);
    if (window_ == nullptr) {
      glfwTerminate();
      throw Error("track --pick: cannot create an OpenGL 3.3 core window on this display");
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(1);
    glfwSetWindowUserPointer(window_, this);
    // Installed before ImGui's, which call them after their own.
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
      auto* self = static_cast<PickWindow*>(glfwGetWindowUserPointer(w));
      if ((action != GLFW_PRESS && action != GLFW_REPEAT) || self->Scripted()) return;
      self->RealKey(key);
    });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
      auto* self = static_cast<PickWindow*>(glfwGetWindowUserPointer(w));
      if (self->Scripted()) return;
      double x = 0, y = 0;
      glfwGetCursorPos(w, &x, &y);
      self->RealButton(button, action, Eigen::Vector2d(x, y));
    });
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
      auto* self = static_cast<PickWindow*>(glfwGetWindowUserPointer(w));
      if (!self->Scripted()) self->RealMove(Eigen::Vector2d(x, y));
    });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) {
      auto* self = static_cast<PickWindow*>(glfwGetWindowUserPointer(w));
      if (self->Scripted()) return;
      double x = 0, y = 0;
      glfwGetCursorPos(w, &x, &y);
      self->view_.ZoomAbout(Eigen::Vector2d(x, y), std::pow(1.25, dy));
    });
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
    imgui_ready_ = true;
  }

  // The frame as a texture drawn with square pixels (nearest), so a zoomed tape stays sharp.
  void Upload(const RgbImage& image) {
    glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, image.width, image.height, 0, GL_RGB, GL_UNSIGNED_BYTE,
                 image.pixels.data());
  }

  // The handlers both the user and the script go through.
  void Click(const Eigen::Vector2d& window_px) {
    const Eigen::Vector2d pixel = view_.ToImage(window_px);
    const MarkerLink* asked = session_.current();
    if (asked != nullptr && session_.Click(pixel)) {
      spdlog::info("pick: marker {} at ({:.1f}, {:.1f})", asked->id, pixel.x(), pixel.y());
      status_.clear();
    } else if (asked != nullptr) {
      status_ = "that is outside the image";
    }
  }
  void Key(const std::string& name) {
    if (name == "backspace") {
      status_ = session_.Undo() ? "" : "nothing to undo";
    } else if (name == "s") {
      status_ = session_.Skip() ? "" : "every marker is answered: Enter writes init.json";
    } else if (name == "enter") {
      if (session_.complete() && !session_.Picked().empty()) {
        finished_ = true;
      } else if (session_.complete()) {
        status_ = "no marker clicked: Backspace to go back, Escape to cancel";
      } else {
        status_ = fmt::format("{} markers left: click or skip (S) each first",
                              session_.count() - session_.index());
      }
    } else if (name == "escape") {
      cancelled_ = true;
    }
  }

  void RealKey(int key) {
    if (key == GLFW_KEY_BACKSPACE) Key("backspace");
    if (key == GLFW_KEY_S) Key("s");
    if (key == GLFW_KEY_ENTER || key == GLFW_KEY_KP_ENTER) Key("enter");
    if (key == GLFW_KEY_ESCAPE) Key("escape");
    const Eigen::Vector2d centre(width_ / 2.0, height_ / 2.0);
    if (key == GLFW_KEY_EQUAL || key == GLFW_KEY_KP_ADD) view_.ZoomAbout(centre, 1.5);
    if (key == GLFW_KEY_MINUS || key == GLFW_KEY_KP_SUBTRACT) view_.ZoomAbout(centre, 1 / 1.5);
    if (key == GLFW_KEY_LEFT) view_.Pan({40, 0});
    if (key == GLFW_KEY_RIGHT) view_.Pan({-40, 0});
    if (key == GLFW_KEY_UP) view_.Pan({0, 40});
    if (key == GLFW_KEY_DOWN) view_.Pan({0, -40});
  }
  void RealButton(int button, int action, const Eigen::Vector2d& at) {
    if (button == GLFW_MOUSE_BUTTON_LEFT && action == GLFW_PRESS) Click(at);
    if (button == GLFW_MOUSE_BUTTON_RIGHT || button == GLFW_MOUSE_BUTTON_MIDDLE) {
      panning_ = action == GLFW_PRESS;
      last_mouse_ = at;
    }
  }
  void RealMove(const Eigen::Vector2d& at) {
    if (panning_) view_.Pan(at - last_mouse_);
    last_mouse_ = at;
  }

  bool Scripted() const { return !options_.script.empty(); }
  void RunScript() {
    if (wait_ > 0) {
      --wait_;
      return;
    }
    if (next_ >= options_.script.size()) return;  // the rest is the user's
    const PickAction& a = options_.script[next_++];
    const std::vector<double>& n = a.numbers;
    switch (a.verb) {
      case PickVerb::kClick:
        Click({n[0], n[1]});
        break;
      case PickVerb::kClickImage:
        Click(view_.ToWindow({n[0], n[1]}));
        break;
      case PickVerb::kZoom:
        view_.ZoomAbout(n.size() == 3 ? Eigen::Vector2d(n[1], n[2])
                                      : Eigen::Vector2d(width_ / 2.0, height_ / 2.0),
                        n[0]);
        break;
      case PickVerb::kPan:
        view_.Pan({n[0], n[1]});
        break;
      case PickVerb::kKey:
        Key(a.key);
        break;
      case PickVerb::kWait:
        wait_ = std::max(0, static_cast<int>(n[0]) - 1);
        break;
    }
  }

  void Draw() {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    const auto at = [](const Eigen::Vector2d& p) {
      return ImVec2(static_cast<float>(p.x()), static_cast<float>(p.y()));
    };
    draw->AddImage(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(texture_)),
                   at(view_.ToWindow({-0.5, -0.5})),
                   at(view_.ToWindow({image_w_ - 0.5, image_h_ - 0.5})));
    // Clicked markers: a ring a little larger than a tape, and the id.
    for (const MarkerPixel& m : session_.Picked()) {
      const ImVec2 c = at(view_.ToWindow(m.pixel));
      draw->AddCircle(c, 7.0f, IM_COL32(40, 255, 90, 255), 16, 2.0f);
      draw->AddText(ImVec2(c.x + 8, c.y - 16), IM_COL32(40, 255, 90, 255),
                    std::to_string(m.id).c_str());
    }
    ImGui::SetNextWindowPos(ImVec2(8, 8));
    ImGui::SetNextWindowBgAlpha(0.75f);
    ImGui::Begin("##pick", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                     ImGuiWindowFlags_NoInputs);
    ImGui::TextUnformatted(session_.Prompt().c_str());
    ImGui::TextDisabled(
        "left click: the marker  Backspace: undo  S: skip  Enter: finish  Esc: cancel  "
        "wheel/+/-: zoom  right-drag/arrows: pan");
    if (!status_.empty()) ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "%s", status_.c_str());
    ImGui::End();
    ImGui::Render();
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window_, &fw, &fh);
    glViewport(0, 0, fw, fh);
    glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    glfwSwapBuffers(window_);
  }

  PickSession session_;
  MarkerPickOptions options_;
  ImageView view_;
  GLFWwindow* window_ = nullptr;
  GLuint texture_ = 0;
  bool imgui_ready_ = false;
  int width_ = 0, height_ = 0, image_w_ = 0, image_h_ = 0;
  bool finished_ = false, cancelled_ = false, panning_ = false;
  Eigen::Vector2d last_mouse_ = Eigen::Vector2d::Zero();
  std::string status_;
  size_t next_ = 0;
  int wait_ = 0, frames_ = 0;
};

}  // namespace

void MarkerPickOptions::Validate() const {
  CheckInRange("max_width", max_width, 64, 16384);
  CheckInRange("max_height", max_height, 64, 16384);
}

MarkerPickResult PickMarkers(const fs::path& pull_dir, const MarkerPickOptions& options) {
  options.Validate();
  const PickInput input = ReadPickInput(pull_dir);
  PickWindow window(input, options);
  while (window.Frame()) {
  }
  if (!window.finished()) {
    throw InputError("--pick", "", "cancelled: no init.json written");
  }
  MarkerPickResult result;
  result.init = window.session().ToInit(input.frame);
  result.frames = window.frames();
  for (const MarkerLink& m : input.markers) {
    const auto& picked = result.init.markers;
    if (std::none_of(picked.begin(), picked.end(),
                     [&](const MarkerPixel& p) { return p.id == m.id; }))
      result.skipped.push_back(m.id);
  }
  return result;
}

}  // namespace simtree::viewer
