#include "simtree/viewer/detail/pick_session.h"

#include <algorithm>

#include <fmt/format.h>

#include "simtree/core/error.h"

namespace simtree::viewer::detail {

PickSession::PickSession(std::vector<MarkerLink> markers, int image_width, int image_height)
    : markers_(std::move(markers)), width_(image_width), height_(image_height) {}

const MarkerLink* PickSession::current() const {
  return complete() ? nullptr : &markers_[answers_.size()];
}

bool PickSession::Click(const Eigen::Vector2d& pixel) {
  if (complete()) return false;
  const bool inside = pixel.x() >= -0.5 && pixel.y() >= -0.5 && pixel.x() < width_ - 0.5 &&
                      pixel.y() < height_ - 0.5;
  if (!inside) return false;
  answers_.emplace_back(pixel);
  return true;
}

bool PickSession::Skip() {
  if (complete()) return false;
  answers_.emplace_back(std::nullopt);
  return true;
}

bool PickSession::Undo() {
  if (answers_.empty()) return false;
  answers_.pop_back();
  return true;
}

std::string PickSession::Prompt() const {
  if (const MarkerLink* m = current()) {
    return fmt::format("click marker {}{} ({} of {})", m->id,
                       m->label.empty() ? "" : " (" + m->label + ")", index() + 1, count());
  }
  const size_t picked = Picked().size();
  return fmt::format("{} of {} markers clicked, {} skipped: Enter writes init.json", picked,
                     count(), count() - picked);
}

std::vector<MarkerPixel> PickSession::Picked() const {
  std::vector<MarkerPixel> out;
  for (size_t i = 0; i < answers_.size(); ++i) {
    if (answers_[i]) out.push_back(MarkerPixel{markers_[i].id, *answers_[i]});
  }
  return out;
}

TrackInit PickSession::ToInit(int frame) const {
  TrackInit init;
  init.frame = frame;
  init.markers = Picked();
  if (init.markers.empty()) {
    throw InputError("--pick", "", "no marker was clicked: nothing to start tracking from");
  }
  return init;
}

ImageView ImageView::Fit(int image_width, int image_height, int window_width, int window_height) {
  ImageView v;
  v.zoom = std::min(static_cast<double>(window_width) / image_width,
                    static_cast<double>(window_height) / image_height);
  // Pixel centres at integers: the image spans [-0.5, width - 0.5].
  const Eigen::Vector2d span(image_width * v.zoom, image_height * v.zoom);
  v.origin = (Eigen::Vector2d(window_width, window_height) - span) / 2.0 +
             Eigen::Vector2d::Constant(0.5 * v.zoom);
  return v;
}

void ImageView::ZoomAbout(const Eigen::Vector2d& window_point, double factor) {
  const Eigen::Vector2d image = ToImage(window_point);
  zoom = std::clamp(zoom * factor, 0.1, 64.0);
  origin = window_point - zoom * image;
}

}  // namespace simtree::viewer::detail
