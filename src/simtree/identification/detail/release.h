#pragma once
// Finding the release instant of a pull test in marker trajectories: the tree is held still
// (pulled), then let go and swings freely. Identification keeps the free decay from there.

#include <string>

#include "simtree/io/trajectories.h"

namespace simtree::identification {

struct ReleaseOptions {
  // A frame moves "a lot" when its speed reaches this share of the record's peak speed; the first
  // such frame is in the first swing after the release. Both count speeds kept for three frames:
  // a lone tracker jump is not a swing.
  double swing_fraction = 0.5;
  // Walking back from there, the release is the last frame whose speed (over about 0.1 s) is below
  // both this share of the peak speed and `noise_factor` times the rms speed noise alone gives.
  double quiet_fraction = 0.1;
  double noise_factor = 3.0;
  // ... and whose speeds stayed that low for this long before it, s (a hold, not a swing's
  // turning point). A marker whose track has a gap between that frame and the swing does not
  // decide when another marker saw the same swing throughout.
  double min_hold_s = 0.2;

  // Throws InputError naming the field for a value out of range.
  void Validate() const;
};

// How the start of the free decay was found.
enum class ReleaseOutcome {
  kDetected,         // a still hold followed by a swing
  kGiven,            // IdentifyOptions::release_time_s
  kTooFewFrames,     // under 3 frames, or no track: the record is taken from its first frame
  kNoMotion,         // no marker moves above its noise: taken from the first frame
  kAlreadySwinging,  // no still frame before the first swing: taken from the first frame
};
// "detected", "given", "too_few_frames", "no_motion", "already_swinging".
const char* ToString(ReleaseOutcome outcome);

struct ReleaseDetection {
  ReleaseOutcome outcome = ReleaseOutcome::kTooFewFrames;
  int frame_index = 0;  // index into Trajectories::frames of the last still frame
  double time_s = 0.0;
  int marker = -1;           // the marker whose motion decided it (the one that moves most)
  double peak_speed = 0.0;   // m/s of that marker
  double noise_speed = 0.0;  // m/s that noise alone gives that marker
  std::string note;          // how it was decided, or why not, for a person

  // The release is known (detected or given), not just the first frame.
  bool found() const {
    return outcome == ReleaseOutcome::kDetected || outcome == ReleaseOutcome::kGiven;
  }
};

// The release of the pull. When the record starts already swinging (no still frames before the
// first swing), or shows no motion above the noise, the first frame is taken and `outcome` says
// why.
ReleaseDetection DetectRelease(const Trajectories& trajectories,
                               const ReleaseOptions& options = {});

// The index of the first frame at or after `time_s` (the frame count when none).
int FrameAtOrAfter(const Trajectories& trajectories, double time_s);

}  // namespace simtree::identification
