#pragma once
// How a marker tracker errs, applied to true marker trajectories: what identification is scored
// on until a tracker runs on the synthetic stream, and what it is stress-tested with after.
//
// A tracker that finds a tape band in the colour image and reads its depth from the depth image
// is off by a pixel or so across the image and by more along the depth axis (the band's depth is
// a median over a noisy, partly mixed patch), it loses a marker now and then for a few frames
// (occlusion, motion blur), and rarely jumps to a wrong blob. The defaults give a 3D RMS error of
// about 2.5 mm, independent from frame to frame (a box found anew in every frame), short gaps on
// about 1% of the frames and a jump on 0.1%. `correlation` > 0 makes the error drift instead: a
// harder case, since correlated noise has power at the swing's own frequencies.

#include <cstdint>
#include <vector>

#include "simtree/io/ground_truth.h"
#include "simtree/io/trajectories.h"

namespace simtree::tracking {

struct TrackerErrorOptions {
  // Root-mean-square 3D error of a tracked position (mm). The depth axis (camera z) gets
  // `depth_ratio` times the standard deviation of each image axis.
  double rms_error_mm = 2.5;
  double depth_ratio = 2.0;
  // Frame-to-frame correlation of the error (AR(1) coefficient, 0 = white).
  double correlation = 0.0;
  // Gaps: the chance per frame that a tracked marker is lost, and the mean length of a loss
  // (frames, geometric).
  double gap_start_rate = 0.002;
  double mean_gap_frames = 5.0;
  // Jumps to a wrong blob: the chance per frame and the size of the jump (mm, uniform direction).
  double jump_rate = 0.001;
  double jump_mm = 40.0;
  uint64_t seed = 1;
};

// The tracked version of `truth`: the same frames and markers, errors and gaps added. When
// `visibility` (gt/markers_2d.json) is given, a marker is also lost wherever the camera did not see
// enough of its tape. Deterministic for a seed. Throws InputError for options out of range or a
// visibility list that does not match the frames.
Trajectories SimulateTrackerError(const Trajectories& truth, const TrackerErrorOptions& options,
                                  const std::vector<MarkerFrame2d>* visibility = nullptr);

}  // namespace simtree::tracking
