#include "simtree/capture_check/detail/tape_check.h"

#include <algorithm>
#include <filesystem>

#include "simtree/io/track_init.h"
#include "simtree/tracking/find_tapes.h"

namespace simtree::capture_check::detail {

namespace {

void Summarise(TapeCheck* t) {
  if (t->widths_px.empty()) return;
  std::vector<double> w = t->widths_px;
  std::sort(w.begin(), w.end());
  t->narrowest_px = w.front();
  t->median_px = w[w.size() / 2];
}

}  // namespace

TapeCheck MeasureTape(const RgbdImage& frame, const PullStream& pull, int frame_number,
                      const std::string& color) {
  TapeCheck t;
  tracking::FindTapesOptions options;
  options.color = color;
  const std::filesystem::path init_path = pull.directory / "init.json";
  if (std::filesystem::exists(init_path)) {
    const TrackInit init = ReadTrackInitJson(init_path);
    t.has_init = init.frame == frame_number;
    // The tracker fits its colour model to the tape at the init pixels.
    if (t.has_init) {
      for (const MarkerPixel& m : init.markers) options.fit_pixels.push_back(m.pixel);
    }
  }
  const std::vector<tracking::TapeSighting> tapes = tracking::FindTapes(frame, options);
  t.blobs = static_cast<int>(tapes.size());
  if (!t.has_init) {
    t.expected = static_cast<int>(pull.markers.size());
    t.found = t.blobs;
    for (const tracking::TapeSighting& s : tapes) t.widths_px.push_back(s.width_px);
    Summarise(&t);
    return t;
  }
  t.expected = static_cast<int>(options.fit_pixels.size());
  for (const int i : tracking::TapesAtPixels(tapes, options.fit_pixels, frame)) {
    if (i < 0) continue;
    ++t.found;
    t.widths_px.push_back(tapes[i].width_px);
  }
  Summarise(&t);
  return t;
}

}  // namespace simtree::capture_check::detail
