#include "simtree/viewer/detail/offscreen_context.h"

#define EGL_EGLEXT_PROTOTYPES 1
#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/viewer/detail/gl_objects.h"
#include "simtree/viewer/scene_renderer.h"
#include "simtree/viewer/xvfb.h"

namespace simtree::viewer {
namespace {

// A current context from EGL's surfaceless platform, or an error message.
struct EglContext {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;

  std::string Create() {
    display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) return "no EGL surfaceless platform";
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
      display = EGL_NO_DISPLAY;
      return fmt::format("eglInitialize failed (0x{:x})", eglGetError());
    }
    if (!eglBindAPI(EGL_OPENGL_API)) return "EGL has no desktop OpenGL";
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                 3,
                                 EGL_CONTEXT_MINOR_VERSION,
                                 3,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_NONE};
    context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context == EGL_NO_CONTEXT) {
      return fmt::format("no OpenGL 3.3 core context (0x{:x})", eglGetError());
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
      return fmt::format("eglMakeCurrent failed (0x{:x})", eglGetError());
    }
    return "";
  }
  ~EglContext() {
    if (display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    eglTerminate(display);
  }
};

}  // namespace

struct OffscreenContext::Impl {
  OffscreenOptions options;
  std::string description;
  std::unique_ptr<EglContext> egl;
  std::unique_ptr<ScopedXvfb> xvfb;
  GLFWwindow* window = nullptr;
  gl::Framebuffer draw_fbo, resolve_fbo;
  gl::Renderbuffer colour, depth, resolved;

  std::string TryEgl() {
    egl = std::make_unique<EglContext>();
    const std::string error = egl->Create();
    if (!error.empty()) egl.reset();
    return error;
  }

  std::string TryGlfw() {
    if (!HasDisplay()) xvfb = std::make_unique<ScopedXvfb>(options.width, options.height);
    if (!glfwInit()) return "GLFW cannot start on the X display";
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window = glfwCreateWindow(64, 64, "simtree render", nullptr, nullptr);
    if (window == nullptr) {
      glfwTerminate();
      return "no OpenGL 3.3 core context on the X display";
    }
    glfwMakeContextCurrent(window);
    return "";
  }

  void MakeFramebuffer() {
    auto renderbuffer = [](GLenum format, int samples, int w, int h) {
      GLuint id = 0;
      glGenRenderbuffers(1, &id);
      glBindRenderbuffer(GL_RENDERBUFFER, id);
      glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, format, w, h);
      return gl::Renderbuffer(id);
    };
    GLint max_samples = 0;
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    const int samples = std::clamp(options.samples, 0, static_cast<int>(max_samples));
    GLuint id = 0;
    glGenFramebuffers(1, &id);
    draw_fbo = gl::Framebuffer(id);
    colour = renderbuffer(GL_RGBA8, samples, options.width, options.height);
    depth = renderbuffer(GL_DEPTH_COMPONENT24, samples, options.width, options.height);
    glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth.id());
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw Error("OpenGL: the offscreen framebuffer is incomplete");
    }
    glGenFramebuffers(1, &id);
    resolve_fbo = gl::Framebuffer(id);
    resolved = renderbuffer(GL_RGBA8, 0, options.width, options.height);
    glBindFramebuffer(GL_FRAMEBUFFER, resolve_fbo.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolved.id());
    glBindFramebuffer(GL_FRAMEBUFFER, draw_fbo.id());
    gl::CheckErrors("making the offscreen framebuffer");
  }
};

void ValidateFramebuffer(int width, int height, int samples, const std::string& source) {
  CheckOption(width >= 1 && width <= 16384, source, "width",
              fmt::format("expected 1-16384 pixels, got {}", width));
  CheckOption(height >= 1 && height <= 16384, source, "height",
              fmt::format("expected 1-16384 pixels, got {}", height));
  CheckOption(samples >= 0 && samples <= 16, source, "samples",
              fmt::format("expected 0 to 16 samples, got {}", samples));
}

void OffscreenOptions::Validate() const {
  const std::string source = "offscreen options";
  ValidateFramebuffer(width, height, samples, source);
  CheckOption(backend == OffscreenBackend::kAuto || backend == OffscreenBackend::kEgl ||
                  backend == OffscreenBackend::kXvfb,
              source, "backend",
              fmt::format("expected auto, egl or xvfb, got {}", static_cast<int>(backend)));
}

OffscreenContext::OffscreenContext(const OffscreenOptions& options)
    : impl_(std::make_unique<Impl>()) {
  options.Validate();
  Impl& m = *impl_;
  m.options = options;
  std::string egl_error = "not tried";
  if (options.backend != OffscreenBackend::kXvfb) {
    egl_error = m.TryEgl();
    if (egl_error.empty()) m.description = "EGL surfaceless";
  }
  if (m.description.empty() && options.backend != OffscreenBackend::kEgl) {
    if (options.backend == OffscreenBackend::kAuto) {
      spdlog::info("render: EGL gives no headless OpenGL here ({}); using an X display", egl_error);
    }
    const std::string glfw_error = m.TryGlfw();
    if (!glfw_error.empty()) {
      throw Error(fmt::format("render: no headless OpenGL: EGL: {}; X: {}", egl_error, glfw_error));
    }
    m.description = m.xvfb ? "Xvfb " + m.xvfb->display() : "X display";
  }
  if (m.description.empty()) throw Error("render: no headless OpenGL: EGL: " + egl_error);
  m.description += ": " + gl::RendererName();
  m.MakeFramebuffer();
}

OffscreenContext::~OffscreenContext() {
  Impl& m = *impl_;
  // GL objects go while the context is still current.
  m.draw_fbo.Reset();
  m.resolve_fbo.Reset();
  m.colour.Reset();
  m.depth.Reset();
  m.resolved.Reset();
  if (m.window != nullptr) {
    glfwDestroyWindow(m.window);
    glfwTerminate();
  }
  m.egl.reset();
}

int OffscreenContext::width() const { return impl_->options.width; }
int OffscreenContext::height() const { return impl_->options.height; }
const std::string& OffscreenContext::description() const { return impl_->description; }

void OffscreenContext::Bind() {
  glBindFramebuffer(GL_FRAMEBUFFER, impl_->draw_fbo.id());
  glViewport(0, 0, width(), height());
}

RgbImage OffscreenContext::Read() {
  Impl& m = *impl_;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, m.draw_fbo.id());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m.resolve_fbo.id());
  glBlitFramebuffer(0, 0, width(), height(), 0, 0, width(), height(), GL_COLOR_BUFFER_BIT,
                    GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, m.resolve_fbo.id());
  RgbImage image = ReadPixels(width(), height());
  Bind();
  return image;
}

}  // namespace simtree::viewer
