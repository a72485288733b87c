#include "simtree/synth/detail/init_clicks.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "simtree/core/error.h"
#include "simtree/synth/detail/sensor_random.h"

namespace simtree::synth {

void InitClickOptions::Validate() const {
  if (!(noise_px >= 0.0 && noise_px <= 50.0)) {
    throw InputError("init click options", "noise_px",
                     fmt::format("expected 0-50 px, got {}", noise_px));
  }
}

TrackInit SimulateInitClicks(const std::vector<MarkerFrame2d>& frames, int width, int height,
                             const InitClickOptions& options) {
  options.Validate();
  if (width <= 0 || height <= 0) {
    throw InputError("init clicks", "image size",
                     fmt::format("expected a positive size, got {}x{}", width, height));
  }
  const auto shows_a_marker = [](const MarkerFrame2d& f) {
    return std::any_of(f.markers.begin(), f.markers.end(),
                       [](const MarkerBox2d& m) { return m.visible; });
  };
  const auto first = std::find_if(frames.begin(), frames.end(), shows_a_marker);
  if (first == frames.end()) {
    throw InputError(
        "init clicks", "markers_2d",
        fmt::format("expected a frame showing a marker; none of {} frames does", frames.size()));
  }
  TrackInit init;
  init.frame = first->frame;
  for (const MarkerBox2d& m : first->markers) {
    if (!m.visible) continue;
    // One random stream per marker id, so adding or hiding a marker moves no other click.
    PixelRandom random(options.seed, static_cast<uint64_t>(init.frame), static_cast<uint64_t>(m.id),
                       RandomStream::kClick);
    const double dx = options.noise_px * random.Normal();
    const double dy = options.noise_px * random.Normal();
    const double cx = m.box[0] + 0.5 * m.box[2];
    const double cy = m.box[1] + 0.5 * m.box[3];
    MarkerPixel click;
    click.id = m.id;
    click.pixel = Eigen::Vector2d(std::clamp(cx + dx, 0.0, width - 1.0),
                                  std::clamp(cy + dy, 0.0, height - 1.0));
    init.markers.push_back(click);
  }
  return init;
}

}  // namespace simtree::synth
