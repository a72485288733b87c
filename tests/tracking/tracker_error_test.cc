#include "simtree/tracking/tracker_error.h"

#include <cmath>

#include <gtest/gtest.h>

#include "simtree/core/error.h"

namespace simtree::tracking {
namespace {

// Two markers swinging for 20 s at 30 fps.
Trajectories Swing(int frames = 600) {
  Trajectories t;
  t.tracks.resize(2);
  t.tracks[0].marker = 0;
  t.tracks[1].marker = 4;
  for (int f = 0; f < frames; ++f) {
    const double time = f / 30.0;
    t.AddFrame(f, time,
               {Eigen::Vector3d(0.1 * std::sin(6 * time), -0.5, 2.0),
                Eigen::Vector3d(0.3, 0.05 * std::cos(7 * time), 2.4)},
               {true, true});
  }
  return t;
}

TEST(TrackerError, ErrorHasTheSetSizeAndShape) {
  const Trajectories truth = Swing(6000);
  TrackerErrorOptions options;
  options.gap_start_rate = 0;
  options.jump_rate = 0;
  options.correlation = 0.6;
  const Trajectories tracked = SimulateTrackerError(truth, options);
  ASSERT_EQ(tracked.frame_count(), truth.frame_count());
  ASSERT_EQ(tracked.marker_count(), 2);
  Eigen::Vector3d sum_sq = Eigen::Vector3d::Zero();
  double lag_product = 0, lag_norm = 0;
  int n = 0;
  for (int m = 0; m < 2; ++m) {
    for (int f = 0; f < truth.frame_count(); ++f) {
      ASSERT_TRUE(tracked.tracks[m].valid[f]);
      const Eigen::Vector3d e = tracked.tracks[m].positions[f] - truth.tracks[m].positions[f];
      sum_sq += e.cwiseAbs2();
      ++n;
      if (f > 0) {
        const Eigen::Vector3d p =
            tracked.tracks[m].positions[f - 1] - truth.tracks[m].positions[f - 1];
        lag_product += e.x() * p.x();
        lag_norm += p.x() * p.x();
      }
    }
  }
  const Eigen::Vector3d rms = (sum_sq / n).cwiseSqrt();
  EXPECT_NEAR(1e3 * rms.norm(), options.rms_error_mm, 0.15);
  EXPECT_NEAR(rms.z() / rms.x(), options.depth_ratio, 0.15);
  EXPECT_NEAR(lag_product / lag_norm, options.correlation, 0.05);
}

TEST(TrackerError, GapsAndJumpsAtAboutTheirRates) {
  const Trajectories truth = Swing(30000);
  TrackerErrorOptions options;
  options.gap_start_rate = 0.01;
  options.mean_gap_frames = 5;
  options.jump_rate = 0.01;
  const Trajectories tracked = SimulateTrackerError(truth, options);
  int lost = 0, jumps = 0, total = 0;
  for (int m = 0; m < 2; ++m) {
    for (int f = 0; f < truth.frame_count(); ++f, ++total) {
      if (!tracked.tracks[m].valid[f]) {
        EXPECT_TRUE(std::isnan(tracked.tracks[m].positions[f].x()));
        ++lost;
      } else if ((tracked.tracks[m].positions[f] - truth.tracks[m].positions[f]).norm() > 0.03) {
        ++jumps;
      }
    }
  }
  // A gap starts at rate r and lasts 1/q frames: lost share r / (r + q) = 0.01 / 0.21.
  EXPECT_NEAR(static_cast<double>(lost) / total, 0.01 / 0.21, 0.01);
  EXPECT_NEAR(static_cast<double>(jumps) / total, 0.01 * (1 - 0.01 / 0.21), 0.003);
}

TEST(TrackerError, InvisibleMarkersAreLostAndSeedsRepeat) {
  const Trajectories truth = Swing(30);
  std::vector<MarkerFrame2d> visibility(30);
  for (int f = 0; f < 30; ++f) {
    visibility[f].frame = f;
    visibility[f].markers = {{0, f < 10, 1.0, 100, {0, 0, 1, 1}},
                             {4, true, 1.0, 100, {0, 0, 1, 1}}};
  }
  TrackerErrorOptions options;
  options.gap_start_rate = 0;
  const Trajectories a = SimulateTrackerError(truth, options, &visibility);
  for (int f = 0; f < 30; ++f) {
    EXPECT_EQ(a.tracks[0].valid[f], f < 10) << f;
    EXPECT_TRUE(a.tracks[1].valid[f]);
  }
  const Trajectories b = SimulateTrackerError(truth, options, &visibility);
  EXPECT_EQ(TrajectoriesToCsv(a), TrajectoriesToCsv(b));
  options.seed = 2;
  EXPECT_NE(TrajectoriesToCsv(a), TrajectoriesToCsv(SimulateTrackerError(truth, options)));
}

TEST(TrackerError, BadOptionsAndMismatchedVisibilityAreRefused) {
  const Trajectories truth = Swing(30);
  TrackerErrorOptions options;
  options.rms_error_mm = std::nan("");
  EXPECT_THROW(SimulateTrackerError(truth, options), InputError);
  options = {};
  options.correlation = 1.0;
  EXPECT_THROW(SimulateTrackerError(truth, options), InputError);
  std::vector<MarkerFrame2d> short_visibility(3);
  EXPECT_THROW(SimulateTrackerError(truth, {}, &short_visibility), InputError);
}

}  // namespace
}  // namespace simtree::tracking
