#pragma once
// What `simtree track --pick` keeps while a person clicks the markers: the markers of
// markers.json in order, the pixel given to each (or skipped), which one is asked for next, and
// undo. No window here: the picking window (pick_markers.h) and its tests drive it.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "simtree/io/capture.h"
#include "simtree/io/track_init.h"

namespace simtree::viewer::detail {

class PickSession {
 public:
  // `markers` in the order they are asked for; `image_width` x `image_height` bound the clicks.
  PickSession(std::vector<MarkerLink> markers, int image_width, int image_height);

  // The marker asked for now (nullptr once every marker was clicked or skipped).
  const MarkerLink* current() const;
  int index() const { return static_cast<int>(answers_.size()); }  // 0-based, of current()
  int count() const { return static_cast<int>(markers_.size()); }
  bool complete() const { return answers_.size() == markers_.size(); }

  // Gives the current marker this image pixel; false (nothing changes) for a pixel outside the
  // image or when complete.
  bool Click(const Eigen::Vector2d& pixel);
  // Skips the current marker (not seen in this frame); false when complete.
  bool Skip();
  // Takes back the last answer (click or skip); false when there is none.
  bool Undo();

  // "click marker 3 (M3) (4 of 12)", or what is left to do once complete.
  std::string Prompt() const;
  // The markers clicked so far, with their pixels, in the order asked.
  std::vector<MarkerPixel> Picked() const;
  // The init of the clicks, at `frame`; throws InputError when nothing was clicked.
  TrackInit ToInit(int frame) const;

 private:
  std::vector<MarkerLink> markers_;
  int width_ = 0, height_ = 0;
  std::vector<std::optional<Eigen::Vector2d>> answers_;  // one per marker answered, nullopt: skip
};

// The window's view of the image: window pixel = origin + zoom * image pixel (image pixel centres
// at integers, so pixel (u, v) covers [u - 0.5, u + 0.5]).
struct ImageView {
  double zoom = 1.0;                                 // window pixels per image pixel
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // window position of image point (0, 0)

  Eigen::Vector2d ToWindow(const Eigen::Vector2d& image) const { return origin + zoom * image; }
  Eigen::Vector2d ToImage(const Eigen::Vector2d& window) const { return (window - origin) / zoom; }
  // The whole image centred in a window of this size.
  static ImageView Fit(int image_width, int image_height, int window_width, int window_height);
  // Zooms by `factor` (clamped to 0.1-64 window pixels an image pixel) keeping the image point
  // under `window_point` where it is.
  void ZoomAbout(const Eigen::Vector2d& window_point, double factor);
  void Pan(const Eigen::Vector2d& window_delta) { origin += window_delta; }
};

}  // namespace simtree::viewer::detail
