#pragma once
// Overlay frames a person can watch: each marker's box (green tracked, yellow predicted, red
// lost: lost markers are not drawn), its id, and its trail over the last frames.

#include <filesystem>

#include "simtree/tracking/track.h"

namespace simtree::tracking::detail {

// Draws frame `index` of `result` over `color` (RGB) and returns the RGB overlay.
RgbImage DrawOverlay(const RgbImage& color, const TrackResult& result, size_t index,
                     int trail_frames);

// Encodes the PNG frames `pattern` (an ffmpeg image pattern, "overlay/%06d.png") at `fps` into
// an H.264 `video`. Throws IoError when the ffmpeg binary is not on PATH or fails.
void EncodeVideo(const std::filesystem::path& pattern, double fps,
                 const std::filesystem::path& video);

}  // namespace simtree::tracking::detail
