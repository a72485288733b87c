#pragma once
// A virtual X display for OpenGL without a screen: starts `Xvfb` on a free display number (it
// picks one itself and tells us through -displayfd), points DISPLAY at it, and stops it again.
// Used by the benchmark and, when EGL cannot give a headless context, by the renderer.

#include <sys/types.h>

#include <optional>
#include <string>

namespace simtree::viewer {

class ScopedXvfb {
 public:
  // Throws simtree::Error when Xvfb is not installed or does not come up within `timeout_s`.
  explicit ScopedXvfb(int width = 1920, int height = 1080, double timeout_s = 10.0);
  ~ScopedXvfb();
  ScopedXvfb(const ScopedXvfb&) = delete;
  ScopedXvfb& operator=(const ScopedXvfb&) = delete;

  const std::string& display() const { return display_; }  // ":93"

 private:
  pid_t pid_ = -1;
  std::string display_;
  std::optional<std::string> previous_display_;
};

// True when DISPLAY names an X server that accepts connections.
bool HasDisplay();

}  // namespace simtree::viewer
