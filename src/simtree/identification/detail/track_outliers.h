#pragma once
// Tracker jumps: a tracker now and then locks onto a wrong blob for a frame or two (another red
// tape, a reflection). One such frame is a 30-50 mm step at 30 fps that bends the path harder
// than any swing does, and it would pass for the release of a pull and put a spike in every
// spectrum. This pass finds them before anything else runs and turns them into gaps.

#include <string>
#include <vector>

#include "simtree/io/trajectories.h"

namespace simtree::identification {

struct TrackOutlierOptions {
  // A sample is compared with a cubic in time fitted by least trimmed squares to the valid
  // samples within `half_window` frames on either side (itself included), the `max_trimmed` (0, 1
  // or 2) that fit worst left out. The cubic follows a swing through its turning points, and
  // trimming keeps a jump of one or two frames out of its neighbours' fits.
  int half_window = 4;  // frames, >= 3 (a cubic and a residual need 6 samples)
  int max_trimmed = 2;  // samples
  // It is an outlier when it is farther from that curve than `threshold` times the track's
  // robust deviation scale, and farther than `min_deviation_m` (so a perfectly clean track does
  // not lose samples to rounding).
  double threshold = 6.0;          // robust deviations
  double min_deviation_m = 0.005;  // m

  // Throws InputError naming the field for a value out of range.
  void Validate() const;
};

struct TrackOutlierReport {
  int removed = 0;                           // samples turned into gaps, over all markers
  std::vector<std::pair<int, int>> samples;  // (marker id, frame index) of each, in order
  std::string note;                          // "removed 3 jumps (markers 2, 5)" or empty
};

// Marks outlying samples invalid (positions NaN) in place.
TrackOutlierReport RemoveTrackOutliers(Trajectories& trajectories,
                                       const TrackOutlierOptions& options = {});

}  // namespace simtree::identification
