#include "simtree/capture_check/detail/tape_check.h"

#include <algorithm>
#include <filesystem>
#include <limits>

#include "simtree/io/track_init.h"
#include "simtree/tracking/detail/blob_detector.h"
#include "simtree/tracking/detail/color_model.h"
#include "simtree/tracking/detail/detection.h"

namespace simtree::capture_check::detail {

namespace tk = simtree::tracking::detail;

namespace {

// The tracker's scales are set at synth's 434 px focal length (tracking/detail/marker_tracker.h).
constexpr double kReferenceFocalPx = 434.19751177064387;
// A blob this near a marker's init pixel (scaled) is that marker's: the tracker's match radius.
constexpr double kMatchRadiusPx = 6.0;

double NarrowSide(const tk::Detection& d) {
  return std::min(2.0 * d.shape.radius, 2.0 * d.shape.half_length);
}

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
  const std::filesystem::path init_path = pull.directory / "init.json";
  std::vector<Eigen::Vector2d> init_pixels;
  if (std::filesystem::exists(init_path)) {
    const TrackInit init = ReadTrackInitJson(init_path);
    t.has_init = init.frame == frame_number;
    for (const MarkerPixel& m : init.markers) init_pixels.push_back(m.pixel);
  }
  // The tracker's colour model, fitted to the tape at the init pixels when there are some.
  tk::TapeColorModel model = tk::ColorModelFromName(color);
  if (t.has_init) {
    model =
        tk::FitColorModel(model, frame.color, init_pixels, std::max(3, frame.color.width / 160));
  }
  tk::BlobDetector detector(model, {});
  const tk::SearchWindow all{0, 0, frame.color.width, frame.color.height};
  std::vector<tk::Detection> detections;
  for (const tk::Blob& blob : detector.Find(frame, {all})) {
    detections.push_back(tk::MeasureBlob(blob, frame, detector, {}));
  }
  t.blobs = static_cast<int>(detections.size());
  if (!t.has_init) {
    t.expected = static_cast<int>(pull.markers.size());
    t.found = t.blobs;
    for (const tk::Detection& d : detections) t.widths_px.push_back(NarrowSide(d));
    Summarise(&t);
    return t;
  }
  t.expected = static_cast<int>(init_pixels.size());
  const double radius = kMatchRadiusPx * frame.intrinsics.fx / kReferenceFocalPx;
  for (const Eigen::Vector2d& p : init_pixels) {
    const tk::Detection* best = nullptr;
    double best_d = std::numeric_limits<double>::infinity();
    for (const tk::Detection& d : detections) {
      const double dist = (d.center - p).norm();
      if (dist < best_d) best_d = dist, best = &d;
    }
    if (best == nullptr || best_d > radius) continue;
    ++t.found;
    t.widths_px.push_back(NarrowSide(*best));
  }
  Summarise(&t);
  return t;
}

}  // namespace simtree::capture_check::detail
