#pragma once
// The tape markers in one pull frame, found as the tracker finds them (tracking/find_tapes.h):
// how many show and how many pixels wide they are.

#include <string>
#include <vector>

#include "simtree/io/capture.h"

namespace simtree::capture_check::detail {

struct TapeCheck {
  int blobs = 0;          // tape blobs in the whole frame
  bool has_init = false;  // pull/init.json was there: markers matched at its pixels
  int expected = 0;       // markers listed in init.json (else markers.json; 0: unknown)
  int found = 0;          // of them, with a blob at their init pixel (without init.json: blobs)
  std::vector<double> widths_px;  // each found marker's band, its narrower side (px)
  double narrowest_px = 0;
  double median_px = 0;
};

// `frame` is frame `frame_index` of `pull`; `color` the tracker's --color ("auto", "red", ...).
TapeCheck MeasureTape(const RgbdImage& frame, const PullStream& pull, int frame_number,
                      const std::string& color);

}  // namespace simtree::capture_check::detail
