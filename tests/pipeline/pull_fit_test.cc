#include "simtree/pipeline/detail/pull_fit.h"

#include <gtest/gtest.h>

#include "pipeline/pulled_scenes.h"
#include "simtree/core/error.h"

using namespace simtree;
using simtree::pipeline::detail::FitPull;
using simtree::pipeline::detail::PullFit;
using simtree::test::PulledScene;
using simtree::test::ReleasedScene;
using simtree::test::Scene;

namespace {

TEST(FitPull, RecoversTheRopePointAndForceOfAStaticPull) {
  const Eigen::Vector3d force(0, 30, -40);
  const double arc = (0.2 + 0.75 * 2.5 / 6) * 1.5;  // one of the candidate points on branch 1
  const Scene s = PulledScene(force, arc);
  pipeline::detail::PullFitOptions static_only;
  static_only.motion_candidates = 0;
  const PullFit fit = FitPull(s.tree, s.tracks, s.world_from_camera, 2.0, {}, static_only);
  EXPECT_FALSE(fit.motion.fitted);
  EXPECT_EQ(fit.branch, 1);
  EXPECT_NEAR(fit.arc_length, arc, 1e-9);
  EXPECT_LT((fit.force - force).norm(), 0.02 * force.norm()) << fit.force.transpose();
  EXPECT_LT(fit.residual_rms_m, 0.02 * fit.observed_rms_m);
  EXPECT_EQ(fit.markers, 4);
  EXPECT_NEAR(fit.hold_s, 0.97, 0.05);
  EXPECT_DOUBLE_EQ(fit.release_s, 2.0);
  const dynamics::PullSchedule schedule = fit.Schedule();
  EXPECT_NEAR(schedule.rope.force_n, fit.force.norm(), 1e-12);
  EXPECT_NO_THROW(schedule.Validate());
}

// A release detected two frames late (as speeds find it) is moved back to the true one by the
// motion after it, to a fraction of a frame; the rope point and force stay.
TEST(FitPull, FitsTheReleaseTimeToTheMotionAfterIt) {
  const Eigen::Vector3d force(0, 30, -40);
  const double arc = (0.2 + 0.75 * 2.5 / 6) * 1.5;
  const double true_release = 3.013;
  const Scene s = ReleasedScene(force, arc, true_release);
  const double detected = true_release + 2.0 / 30.0;
  const PullFit fit = FitPull(s.tree, s.tracks, s.world_from_camera, detected, {});
  ASSERT_TRUE(fit.motion.fitted);
  EXPECT_NEAR(fit.motion.release_s, true_release, 0.005);
  EXPECT_DOUBLE_EQ(fit.detected_release_s, detected);
  EXPECT_EQ(fit.branch, 1);
  EXPECT_NEAR(fit.arc_length, arc, 1e-9);
  EXPECT_LT((fit.force - force).norm(), 0.05 * force.norm()) << fit.force.transpose();
  EXPECT_LT(fit.motion.residual_rms_m, 0.05 * fit.motion.observed_rms_m);
  EXPECT_EQ(fit.motion.markers, 4);
}

// A marker whose track went astray after the release is left out of the motion fit.
TEST(FitPull, LeavesAStrayTrackOutOfTheMotionFit) {
  const Eigen::Vector3d force(0, 30, -40);
  const double arc = (0.2 + 0.75 * 2.5 / 6) * 1.5;
  Scene s = ReleasedScene(force, arc, 3.0);
  MarkerTrack& stray = s.tracks.tracks[3];
  for (int f = 92; f < s.tracks.frame_count(); ++f) {
    stray.positions[f] += Eigen::Vector3d(0.3 * std::sin(f * 0.7), 0.2, 0.0);
  }
  const PullFit fit = FitPull(s.tree, s.tracks, s.world_from_camera, 3.0, {});
  ASSERT_TRUE(fit.motion.fitted);
  EXPECT_EQ(fit.motion.markers, 3);
  EXPECT_NEAR(fit.motion.release_s, 3.0, 0.005);
  EXPECT_LT((fit.force - force).norm(), 0.05 * force.norm()) << fit.force.transpose();
}

TEST(FitPull, LeavesOutExcludedMarkersAndRefusesWhenNothingMoved) {
  const Scene s = PulledScene({0, 30, -40}, 0.625);
  EXPECT_EQ(FitPull(s.tree, s.tracks, s.world_from_camera, 2.0, {2, 3}).markers, 2);
  Scene still = s;
  for (MarkerTrack& t : still.tracks.tracks) {
    for (Eigen::Vector3d& p : t.positions) p = t.positions.front();
  }
  EXPECT_THROW(FitPull(still.tree, still.tracks, still.world_from_camera, 2.0, {}), InputError);
  pipeline::detail::PullFitOptions bad;
  bad.arc_samples = 0;
  EXPECT_THROW(FitPull(s.tree, s.tracks, s.world_from_camera, 2.0, {}, bad), InputError);
}

}  // namespace
