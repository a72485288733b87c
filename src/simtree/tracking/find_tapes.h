#pragma once
// The tape markers visible in one colour + depth frame, found as `track` finds them in its first
// frame: the tape colour model (fitted to the tape at given pixels when there are some), the
// whole frame searched for tape blobs, each blob's sub-pixel centre and the band it shows.
// `capture-check` uses it to say whether a pull stream's tapes show and how wide they are.
//
//   tracking::FindTapesOptions options;
//   options.fit_pixels = {init.markers[0].pixel, ...};  // optional: init.json's pixels
//   const std::vector<tracking::TapeSighting> tapes = tracking::FindTapes(frame, options);
//   const std::vector<int> at = tracking::TapesAtPixels(tapes, options.fit_pixels, frame);

#include <string>
#include <vector>

#include <Eigen/Core>

#include "simtree/io/capture.h"

namespace simtree::tracking {

struct FindTapesOptions {
  // The tape colour, as `track --color`: "auto", "red", "green", "blue", "yellow", "orange" or
  // "#rrggbb".
  std::string color = "auto";
  // Pixels on the tapes (init.json's): the colour model is fitted to the tape around them.
  std::vector<Eigen::Vector2d> fit_pixels;
  // Throws InputError naming the option for a colour that is none of the above.
  void Validate() const;
};

// One tape blob of the frame.
struct TapeSighting {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // px, sub-pixel
  double width_px = 0.0;   // the band's narrower side (the tape's width across the branch)
  double length_px = 0.0;  // its longer side
  int pixel_count = 0;     // tape pixels
};

// The least brightness (max of R, G, B, 0-255) at which the tape colour model reads a colour:
// darker pixels have no hue the tracker can use.
double TapeMinBrightness();

// Every tape blob of `frame`, in the detector's order; the edge pieces a thin tape's blob splits
// into by depth (its anti-aliased pixels read the background) are left out.
std::vector<TapeSighting> FindTapes(const RgbdImage& frame, const FindTapesOptions& options);

// For each pixel, the index into `tapes` of the nearest sighting within the tracker's match radius
// (6 px at track.h's kReferenceFocalPx, scaled with the frame's focal length), or -1.
std::vector<int> TapesAtPixels(const std::vector<TapeSighting>& tapes,
                               const std::vector<Eigen::Vector2d>& pixels, const RgbdImage& frame);

}  // namespace simtree::tracking
