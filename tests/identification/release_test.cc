#include "simtree/identification/detail/release.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/identification/detail/test_signals.h"
#include "simtree/tracking/tracker_error.h"

namespace simtree::identification {
namespace {

// A tracker's errors (default options) on `truth`, drawn with `seed`.
Trajectories Tracked(const Trajectories& truth, uint64_t seed) {
  tracking::TrackerErrorOptions noise;
  noise.seed = seed;
  return tracking::SimulateTrackerError(truth, noise);
}

SyntheticMarkerTree Pulled() {
  SyntheticMarkerTree tree;
  tree.links.resize(1);
  tree.links[0].theta_u = {{1.2, 0.03, 0.15, 0.0}};  // released from 0.15 rad, at rest velocity
  tree.links[0].length_m = 0.8;
  return tree;
}

TEST(Release, FoundAtTheEndOfTheHoldEvenWithTrackerNoise) {
  std::vector<MarkerLink> markers;
  const Trajectories truth = MakeMarkerTrajectories(Pulled(), 30.0, 3.0, 8.0, &markers);
  for (uint64_t seed : {1, 2, 3}) {
    const ReleaseDetection r = DetectRelease(Tracked(truth, seed));
    EXPECT_EQ(r.outcome, ReleaseOutcome::kDetected) << r.note;
    EXPECT_EQ(r.marker, 1);
    // Never before the release (a still frame in the decay would break the model), at most
    // about 0.15 s after it.
    EXPECT_GE(r.time_s, 3.0 - 1e-9) << r.note;
    EXPECT_LE(r.time_s, 3.0 + 0.15) << r.note;
  }
}

// A jump the outlier test missed (one frame 20 cm off during the hold: 2 m/s, twice the swing's
// peak) is two lone spikes of speed, not a swing.
TEST(Release, ALoneTrackerJumpDuringTheHoldIsNotTheRelease) {
  std::vector<MarkerLink> markers;
  const Trajectories truth = MakeMarkerTrajectories(Pulled(), 30.0, 3.0, 8.0, &markers);
  for (uint64_t seed : {1, 2, 3}) {
    Trajectories tracked = Tracked(truth, seed);
    for (MarkerTrack& track : tracked.tracks) {
      const int frame = FrameAtOrAfter(tracked, 1.0);
      track.valid[frame] = true;
      track.positions[frame] += Eigen::Vector3d(0.2, 0, 0);
    }
    const ReleaseDetection r = DetectRelease(tracked);
    EXPECT_EQ(r.outcome, ReleaseOutcome::kDetected) << r.note;
    EXPECT_GE(r.time_s, 3.0 - 1e-9) << r.note;
    EXPECT_LE(r.time_s, 3.0 + 0.15) << r.note;
    EXPECT_LT(r.peak_speed, 1.5) << r.note;
  }
}

// The marker that moves most lost its tape from the pull's start into the swing: the still frame
// before that gap is not the release, and another marker that saw the hold decides.
TEST(Release, AMarkerUnseenThroughTheHoldDoesNotDecide) {
  SyntheticMarkerTree tree = Pulled();
  tree.links.push_back(tree.links[0]);
  tree.links[1].theta_u = {{1.2, 0.03, 0.05, 0.0}};
  std::vector<MarkerLink> markers;
  const Trajectories truth = MakeMarkerTrajectories(tree, 30.0, 3.0, 8.0, &markers);
  for (uint64_t seed : {1, 2, 3}) {
    Trajectories t = Tracked(truth, seed);
    const ReleaseDetection seen = DetectRelease(t);
    ASSERT_EQ(seen.outcome, ReleaseOutcome::kDetected) << seen.note;
    for (MarkerTrack& track : t.tracks) {
      if (track.marker != seen.marker) continue;
      for (int i = FrameAtOrAfter(t, 1.0); i < FrameAtOrAfter(t, 3.3); ++i) track.valid[i] = false;
    }
    const ReleaseDetection r = DetectRelease(t);
    EXPECT_EQ(r.outcome, ReleaseOutcome::kDetected) << r.note;
    EXPECT_NE(r.marker, seen.marker) << r.note;
    EXPECT_GE(r.time_s, 3.0 - 1e-9) << r.note;
    EXPECT_LE(r.time_s, 3.0 + 0.15) << r.note;
  }
}

TEST(Release, ARecordThatStartsSwingingOrNeverMovesStartsAtItsFirstFrame) {
  std::vector<MarkerLink> markers;
  const ReleaseDetection swinging =
      DetectRelease(MakeMarkerTrajectories(Pulled(), 30.0, 0.0, 5.0, &markers));
  EXPECT_EQ(swinging.outcome, ReleaseOutcome::kAlreadySwinging) << swinging.note;
  EXPECT_FALSE(swinging.found());
  EXPECT_EQ(swinging.frame_index, 0);

  SyntheticMarkerTree still = Pulled();
  still.links[0].theta_u.clear();
  const ReleaseDetection flat = DetectRelease(
      tracking::SimulateTrackerError(MakeMarkerTrajectories(still, 30.0, 1.0, 5.0, &markers), {}));
  EXPECT_EQ(flat.outcome, ReleaseOutcome::kNoMotion) << flat.note;
  EXPECT_FALSE(flat.found());
  EXPECT_EQ(flat.frame_index, 0);
}

TEST(Release, FrameAtOrAfter) {
  Trajectories t;
  t.tracks = {MarkerTrack{0, {}, {}}};
  for (int i = 0; i < 5; ++i) t.AddFrame(i, 0.5 * i, {Eigen::Vector3d::Zero()}, {true});
  EXPECT_EQ(FrameAtOrAfter(t, 0.0), 0);
  EXPECT_EQ(FrameAtOrAfter(t, 0.7), 2);
  EXPECT_EQ(FrameAtOrAfter(t, 1.0), 2);
  EXPECT_EQ(FrameAtOrAfter(t, 9.0), 5);
}

}  // namespace
}  // namespace simtree::identification
