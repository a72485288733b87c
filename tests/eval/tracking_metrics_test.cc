#include "simtree/eval/tracking_metrics.h"

#include <cmath>

#include <gtest/gtest.h>

#include "simtree/core/error.h"

namespace simtree::eval {
namespace {

using tracking::FrameBoxes;
using tracking::MarkerBox;
using tracking::MarkerState;

// Two markers over `n` frames: truth boxes 10x10 at x = 0 and x = 100, positions 0.5 m apart.
struct Fixture {
  std::vector<MarkerFrame2d> truth_boxes;
  Trajectories truth, tracked;
  std::vector<FrameBoxes> boxes;

  explicit Fixture(int n) {
    for (int m = 0; m < 2; ++m) {
      truth.tracks.push_back(MarkerTrack{m, {}, {}});
      tracked.tracks.push_back(MarkerTrack{m, {}, {}});
    }
    for (int f = 0; f < n; ++f) {
      MarkerFrame2d gt{f, f / 30.0, {}};
      FrameBoxes fb{f, {}};
      std::vector<Eigen::Vector3d> p;
      for (int m = 0; m < 2; ++m) {
        gt.markers.push_back(MarkerBox2d{m, true, 1.0, 50, {100.0 * m, 0, 10, 10}});
        fb.markers.push_back(
            MarkerBox{m, {100.0 * m, 0, 10, 10}, {100.0 * m + 5, 5}, MarkerState::kTracked, 1.0});
        p.push_back(Eigen::Vector3d(0.5 * m, 0, 2));
      }
      truth_boxes.push_back(gt);
      boxes.push_back(fb);
      truth.AddFrame(f, f / 30.0, p, {true, true});
      tracked.AddFrame(f, f / 30.0, p, {true, true});
    }
  }
};

TEST(TrackingMetrics, BoxIou) {
  EXPECT_DOUBLE_EQ(BoxIou({0, 0, 10, 10}, {0, 0, 10, 10}), 1.0);
  EXPECT_NEAR(BoxIou({0, 0, 10, 10}, {5, 0, 10, 10}), 50.0 / 150.0, 1e-12);
  EXPECT_EQ(BoxIou({0, 0, 10, 10}, {20, 0, 10, 10}), 0.0);
  EXPECT_EQ(BoxIou({0, 0, 0, 10}, {0, 0, 10, 10}), 0.0);
}

TEST(TrackingMetrics, PerfectTrackingScoresOne) {
  const Fixture fx(10);
  const TrackingScores s = ScoreTracking(fx.boxes, fx.tracked, fx.truth_boxes, fx.truth);
  EXPECT_EQ(s.visible_samples, 20);
  EXPECT_DOUBLE_EQ(s.tracked_fraction, 1.0);
  EXPECT_NEAR(s.success_rate, 20.0 / 21.0, 1e-12);  // IoU 1 is not > 1
  EXPECT_DOUBLE_EQ(s.precision, 1.0);
  EXPECT_DOUBLE_EQ(s.recall, 1.0);
  EXPECT_DOUBLE_EQ(s.f_score, 1.0);
  EXPECT_DOUBLE_EQ(s.median_error_mm, 0.0);
  EXPECT_EQ(s.swap_events, 0);
}

TEST(TrackingMetrics, LostSamplesLowerRecallNotPrecision) {
  Fixture fx(10);
  for (int f = 0; f < 5; ++f) {
    fx.boxes[f].markers[1].state = MarkerState::kLost;
    fx.boxes[f].markers[1].confidence = 0.0;
    fx.tracked.tracks[1].valid[f] = false;
  }
  const TrackingScores s = ScoreTracking(fx.boxes, fx.tracked, fx.truth_boxes, fx.truth);
  EXPECT_DOUBLE_EQ(s.precision, 1.0);
  EXPECT_DOUBLE_EQ(s.recall, 15.0 / 20.0);
  EXPECT_NEAR(s.f_score, 2 * 0.75 / 1.75, 1e-12);
  EXPECT_DOUBLE_EQ(s.tracked_fraction, 0.75);
}

TEST(TrackingMetrics, ReportsOfHiddenMarkersLowerPrecisionAndTheBestThresholdDropsThem) {
  Fixture fx(10);
  for (int f = 0; f < 10; ++f) fx.truth_boxes[f].markers[1].visible = false;
  for (int f = 0; f < 10; ++f) fx.boxes[f].markers[1].confidence = 0.3;
  const TrackingScores s = ScoreTracking(fx.boxes, fx.tracked, fx.truth_boxes, fx.truth);
  EXPECT_EQ(s.visible_samples, 10);
  EXPECT_DOUBLE_EQ(s.f_threshold, 1.0);  // above the hidden reports' 0.3
  EXPECT_DOUBLE_EQ(s.precision, 1.0);
  EXPECT_EQ(s.tracked_invisible, 10);
}

TEST(TrackingMetrics, ErrorsAndSwapsAreCounted) {
  Fixture fx(10);
  for (int f = 3; f < 6; ++f) {  // marker 0 jumps onto marker 1 for three frames: one event
    fx.tracked.tracks[0].positions[f] = Eigen::Vector3d(0.5, 0, 2.001);
  }
  fx.tracked.tracks[1].positions[8] += Eigen::Vector3d(0, 0.004, 0);
  const TrackingScores s = ScoreTracking(fx.boxes, fx.tracked, fx.truth_boxes, fx.truth);
  EXPECT_EQ(s.swap_samples, 3);
  EXPECT_EQ(s.swap_events, 1);
  EXPECT_NEAR(s.p95_error_mm, 500.0, 1.0);
  EXPECT_DOUBLE_EQ(s.median_error_mm, 0.0);
  EXPECT_EQ(s.markers[0].swap_samples, 3);
}

TEST(TrackingMetrics, NoSharedFrameIsAnError) {
  Fixture fx(3);
  for (auto& b : fx.boxes) b.frame += 100;
  EXPECT_THROW(ScoreTracking(fx.boxes, fx.tracked, fx.truth_boxes, fx.truth), InputError);
}

}  // namespace
}  // namespace simtree::eval
