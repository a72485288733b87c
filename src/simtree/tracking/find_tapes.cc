#include "simtree/tracking/find_tapes.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "simtree/tracking/detail/blob_detector.h"
#include "simtree/tracking/detail/color_model.h"
#include "simtree/tracking/detail/detection.h"
#include "simtree/tracking/track.h"

namespace simtree::tracking {

namespace {

// A blob this near a pixel (at kReferenceFocalPx) is the marker's there: the tracker's own
// first-frame match radius.
constexpr double kTapeMatchRadiusPx = 6.0;
// A piece split by depth from a blob, this near (at kReferenceFocalPx) a piece of the same blob
// with over twice its pixels, is that tape's edge: its anti-aliased pixels read the background's
// depth. The tracker's fragment distance.
constexpr double kTapeFragmentPx = 8.0;

detail::TapeColorModel TapeModelFor(const RgbdImage& frame, const FindTapesOptions& options) {
  const detail::TapeColorModel prior = detail::ColorModelFromName(options.color);
  if (options.fit_pixels.empty()) return prior;
  return detail::FitColorModel(prior, frame.color, options.fit_pixels,
                               std::max(3, frame.color.width / 160));
}

// Drops the edge pieces of split blobs (kTapeFragmentPx); crossing tapes, two pieces of like
// size, both stay.
std::vector<detail::Detection> WithoutFragments(std::vector<detail::Detection> pieces,
                                                double scale) {
  std::vector<detail::Detection> kept;
  for (const detail::Detection& piece : pieces) {
    const bool fragment =
        std::any_of(pieces.begin(), pieces.end(), [&](const detail::Detection& other) {
          return other.source == piece.source && other.pixel_count > 2 * piece.pixel_count &&
                 (other.center - piece.center).norm() <= kTapeFragmentPx * scale;
        });
    if (!fragment) kept.push_back(piece);
  }
  return kept;
}

TapeSighting SightingOf(const detail::Detection& d) {
  TapeSighting s;
  s.center = d.center;
  s.width_px = std::min(2.0 * d.shape.radius, 2.0 * d.shape.half_length);
  s.length_px = std::max(2.0 * d.shape.radius, 2.0 * d.shape.half_length);
  s.pixel_count = d.pixel_count;
  return s;
}

}  // namespace

void FindTapesOptions::Validate() const { detail::ColorModelFromName(color); }

double TapeMinBrightness() { return detail::TapeColorModel{}.min_value; }

std::vector<TapeSighting> FindTapes(const RgbdImage& frame, const FindTapesOptions& options) {
  options.Validate();
  detail::BlobDetector detector(TapeModelFor(frame, options), {});
  const detail::SearchWindow whole_frame{0, 0, frame.color.width, frame.color.height};
  std::vector<detail::Detection> pieces;
  for (const detail::Blob& blob : detector.Find(frame, {whole_frame})) {
    pieces.push_back(detail::MeasureBlob(blob, frame, detector, {}));
  }
  std::vector<TapeSighting> tapes;
  for (const detail::Detection& d :
       WithoutFragments(std::move(pieces), frame.intrinsics.fx / kReferenceFocalPx)) {
    tapes.push_back(SightingOf(d));
  }
  return tapes;
}

std::vector<int> TapesAtPixels(const std::vector<TapeSighting>& tapes,
                               const std::vector<Eigen::Vector2d>& pixels, const RgbdImage& frame) {
  const double radius = kTapeMatchRadiusPx * frame.intrinsics.fx / kReferenceFocalPx;
  std::vector<int> at;
  at.reserve(pixels.size());
  for (const Eigen::Vector2d& p : pixels) {
    int best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int i = 0; i < static_cast<int>(tapes.size()); ++i) {
      const double distance = (tapes[i].center - p).norm();
      if (distance < best_distance) best_distance = distance, best = i;
    }
    at.push_back(best_distance <= radius ? best : -1);
  }
  return at;
}

}  // namespace simtree::tracking
