#pragma once
// pull/init.json as a person would give it: for each marker visible in the pull stream's first
// frame, the pixel a click on it lands on. The click aims at the centre of the tape band's
// projection (gt/markers_2d.json's box centre) and misses by a seeded Gaussian error per axis, as
// a hand on a mouse or a tablet does.
//
//   const TrackInit init = SimulateInitClicks(boxes, width, height, {.seed = seed});
//   WriteTrackInitJson(init, pull / "init.json");

#include <cstdint>
#include <vector>

#include "simtree/io/ground_truth.h"
#include "simtree/io/track_init.h"

namespace simtree::synth {

struct InitClickOptions {
  double noise_px = 1.5;  // standard deviation of the click's error per axis, px (0: exact)
  uint64_t seed = 0;
  void Validate() const;  // throws InputError naming the field
};

// The clicks on the first frame of `frames` in which any marker is visible (frame 0 of a synth
// capture: tapes hidden at rest are moved), one per visible marker in markers.json order, each
// clamped into the image [0, width - 1] x [0, height - 1]. Throws InputError when no frame shows a
// marker or the image size is not positive.
TrackInit SimulateInitClicks(const std::vector<MarkerFrame2d>& frames, int width, int height,
                             const InitClickOptions& options = {});

}  // namespace simtree::synth
