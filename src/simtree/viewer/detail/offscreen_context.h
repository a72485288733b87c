#pragma once
// OpenGL with no window: an OpenGL 3.3 core context and a framebuffer of a given size to draw
// into and read back. What works on a machine without a display, in order:
//   1. EGL on Mesa's surfaceless platform (no X server at all; llvmpipe on a machine without GPU);
//   2. an invisible GLFW window on the X display, starting Xvfb first when there is none.
// The choice is logged and kept in description().

#include <memory>
#include <string>

#include "simtree/io/image_io.h"

namespace simtree::viewer {

enum class OffscreenBackend { kAuto, kEgl, kXvfb };

struct OffscreenOptions {
  int width = 1280;  // pixels, 1 to 16384
  int height = 720;  // pixels, 1 to 16384
  int samples = 4;   // multisample anti-aliasing samples per pixel (0 = off, at most 16)
  OffscreenBackend backend = OffscreenBackend::kAuto;  // kAuto: EGL, else Xvfb

  // Throws InputError ("offscreen options", the field) for a value out of range.
  void Validate() const;
};

// The size and multisampling of a framebuffer, window or offscreen: 1 to 16384 pixels each way,
// 0 to 16 samples. Throws InputError(source, "width" / "height" / "samples", ...) otherwise.
void ValidateFramebuffer(int width, int height, int samples, const std::string& source);

class OffscreenContext {
 public:
  // Makes the context current. Throws InputError for options out of range, and simtree::Error
  // naming what failed when no backend works.
  explicit OffscreenContext(const OffscreenOptions& options);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  int width() const;
  int height() const;
  // Binds the framebuffer for drawing.
  void Bind();
  // Resolves the multisampled framebuffer and reads it, top row first.
  RgbImage Read();
  // "EGL surfaceless: llvmpipe (LLVM 15.0.6, 256 bits) (OpenGL 4.5 (Core Profile) Mesa 22.3.6)".
  const std::string& description() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace simtree::viewer
