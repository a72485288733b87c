#pragma once
// Scores of a marker tracking (`track`'s boxes.csv and trajectories.csv) against synth's truth
// (gt/markers_2d.json, gt/trajectories.csv): the paper's Table III columns as RGB-D tracking
// benchmarks define them (docs/tracking.md, "Metrics"), the centre error in pixels, the 3D error
// in millimetres, identity swaps and the share of visible samples tracked.
//
// A sample is one marker in one frame. It is visible when the truth says enough of its tape shows
// (MarkerBox2d::visible); the tracker reports it when its state is not lost (tracked or
// predicted) and its confidence reaches the threshold tau.
//  - IoU: of the reported box and the true box (0 when either is missing).
//  - Success rate: the area under the success curve, the share of visible samples whose IoU
//    exceeds t, for t in 0, 0.05, ..., 1 (21 thresholds averaged).
//  - Precision(tau): the mean IoU over the samples reported (a report of an invisible marker
//    scores 0); Recall(tau): the mean IoU over the visible samples (a visible marker not reported
//    scores 0); F(tau) = 2 Pr Re / (Pr + Re). Precision, recall and F-score are at the tau giving
//    the largest F (the RGB-D benchmarks' convention).
//  - Identity swap: a tracked sample whose measured 3D centre lies within `swap_distance_mm` of
//    another marker's true centre and farther than that from its own; an event is a run of such
//    samples of one marker.

#include <array>
#include <vector>

#include "simtree/io/ground_truth.h"
#include "simtree/io/trajectories.h"
#include "simtree/tracking/track.h"

namespace simtree::eval {

struct TrackingScoreOptions {
  double swap_distance_mm = 20.0;  // see "Identity swap" above (mm)
  int success_thresholds = 21;     // IoU thresholds from 0 to 1 of the success curve
};

struct MarkerTrackingScore {
  int marker = 0;
  int visible = 0;               // visible samples
  int tracked_visible = 0;       // of them, tracked (measured)
  double median_error_mm = 0.0;  // 3D, over tracked samples with a true position; NaN if none
  int swap_samples = 0;
};

struct TrackingScores {
  int frames = 0;
  int visible_samples = 0;
  int tracked_visible = 0;        // visible samples the tracker measured
  double tracked_fraction = 0.0;  // tracked_visible / visible_samples
  int tracked_invisible = 0;      // samples measured where the truth says the tape is hidden
  double success_rate = 0.0;
  double precision = 0.0, recall = 0.0, f_score = 0.0;
  double f_threshold = 0.0;  // the confidence tau of the F-score
  double mean_iou = 0.0;     // over visible samples
  double median_center_error_px = 0.0, mean_center_error_px = 0.0;  // visible and tracked
  int error_samples = 0;  // tracked samples with a valid true 3D position
  double median_error_mm = 0.0, mean_error_mm = 0.0, p95_error_mm = 0.0;
  int swap_samples = 0, swap_events = 0;
  std::vector<double> success_curve;  // share of visible samples with IoU > t, per threshold
  std::vector<MarkerTrackingScore> markers;
};

// Intersection over union of two [x, y, w, h] boxes (0 when either is empty).
double BoxIou(const std::array<double, 4>& a, const std::array<double, 4>& b);

// Scores the frames present in all four inputs (matched by frame number) and the markers present
// in the truth. Throws InputError when they share no frame or a tracked marker is not in the
// truth.
TrackingScores ScoreTracking(const std::vector<tracking::FrameBoxes>& boxes,
                             const Trajectories& tracked,
                             const std::vector<MarkerFrame2d>& truth_boxes,
                             const Trajectories& truth, const TrackingScoreOptions& options = {});

}  // namespace simtree::eval
