#include "simtree/identification/detail/track_outliers.h"

#include <cmath>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/identification/detail/release.h"

namespace simtree::identification {
namespace {

// One marker held still for 2 s, then swinging at 1 Hz with 8 cm amplitude, 2 mm noise.
Trajectories HeldThenSwinging(uint64_t seed) {
  Trajectories t;
  t.tracks = {MarkerTrack{3, {}, {}}};
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.002 / std::sqrt(3.0));
  for (int f = 0; f < 300; ++f) {
    const double time = f / 30.0;
    const double swing =
        time < 2.0 ? 0.08 : 0.08 * std::exp(-0.2 * (time - 2)) * std::cos(6.2832 * (time - 2));
    t.AddFrame(f, time, {Eigen::Vector3d(swing + noise(rng), noise(rng), 2.0 + noise(rng))},
               {true});
  }
  return t;
}

TEST(TrackOutliers, JumpsBecomeGapsAndNothingElseDoes) {
  Trajectories t = HeldThenSwinging(1);
  const Trajectories clean = t;
  t.tracks[0].positions[30] += Eigen::Vector3d(0.03, -0.02, 0.0);  // while held
  t.tracks[0].positions[100] += Eigen::Vector3d(0.0, 0.0, -0.04);  // mid swing
  t.tracks[0].positions[101] += Eigen::Vector3d(0.0, 0.0, -0.04);  // two frames long
  const TrackOutlierReport report = RemoveTrackOutliers(t);
  EXPECT_EQ(report.removed, 3) << report.note;
  EXPECT_FALSE(t.tracks[0].valid[30]);
  EXPECT_FALSE(t.tracks[0].valid[100]);
  EXPECT_FALSE(t.tracks[0].valid[101]);
  EXPECT_THAT(report.note, ::testing::HasSubstr("marker 3"));

  Trajectories untouched = clean;
  EXPECT_EQ(RemoveTrackOutliers(untouched).removed, 0);
}

// The swing of a pulled twig after release: 20 cm at 2 Hz, no tracker error at all. Each turning
// point lies up to 6 cm beyond the median of its six neighbours, which the earlier median test took
// for a jump at every turn; none of it is one.
TEST(TrackOutliers, AFastErrorFreeSwingLosesNothing) {
  Trajectories t;
  t.tracks = {MarkerTrack{5, {}, {}}};
  for (int f = 0; f < 300; ++f) {
    const double time = f / 30.0;
    const double swing = 0.2 * std::exp(-0.5 * time) * std::cos(2.0 * M_PI * 2.0 * time);
    t.AddFrame(f, time, {Eigen::Vector3d(swing, 0.3 * swing, 2.0)}, {true});
  }
  Trajectories jumped = t;
  const TrackOutlierReport report = RemoveTrackOutliers(t);
  EXPECT_EQ(report.removed, 0) << report.note;

  // A 4 cm jump on the same swing, at its first turning point, is still found.
  jumped.tracks[0].positions[15] += Eigen::Vector3d(0.0, 0.04, 0.0);
  const TrackOutlierReport found = RemoveTrackOutliers(jumped);
  EXPECT_EQ(found.removed, 1) << found.note;
  EXPECT_FALSE(jumped.tracks[0].valid[15]);
}

TEST(TrackOutliers, AJumpWhileHeldIsNotTakenForTheRelease) {
  Trajectories t = HeldThenSwinging(2);
  t.tracks[0].positions[20] += Eigen::Vector3d(0.04, 0.0, 0.0);
  RemoveTrackOutliers(t);
  const ReleaseDetection release = DetectRelease(t);
  EXPECT_EQ(release.outcome, ReleaseOutcome::kDetected) << release.note;
  EXPECT_NEAR(release.time_s, 2.0, 0.15) << release.note;
}

}  // namespace
}  // namespace simtree::identification
