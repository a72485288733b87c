// Playback: measured tracks read in either frame, interpolated in time, and compared against the
// simulated markers; a simulated run played back against itself has no error.

#include "simtree/viewer/marker_playback.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/dynamics/live_pull.h"
#include "simtree/dynamics/recorders.h"
#include "viewer_fixtures.h"

namespace simtree::viewer {
namespace {

using ::testing::HasSubstr;

Trajectories TwoFrames() {
  Trajectories t;
  t.tracks.resize(2);
  t.tracks[0].marker = 4;
  t.tracks[1].marker = 7;
  t.AddFrame(0, 0.0, {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 1, 1)}, {true, true});
  t.AddFrame(1, 0.5, {Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(0, 0, 0)}, {true, false});
  return t;
}

TEST(MarkerPlayback, TrackPositionsInterpolateAndStopAtGaps) {
  const Trajectories t = TwoFrames();
  EXPECT_TRUE(TrackPositionAt(t, 0, 0.25)->isApprox(Eigen::Vector3d(0, 0, 1.5)));
  EXPECT_TRUE(TrackPositionAt(t, 0, 0.5)->isApprox(Eigen::Vector3d(0, 0, 2)));
  EXPECT_TRUE(TrackPositionAt(t, 1, 0.0)->isApprox(Eigen::Vector3d(1, 1, 1)));
  EXPECT_FALSE(TrackPositionAt(t, 1, 0.25).has_value());  // next to an invalid frame
  EXPECT_FALSE(TrackPositionAt(t, 0, 0.6).has_value());   // after the record
  EXPECT_FALSE(TrackPositionAt(t, 0, std::nan("")).has_value());
  EXPECT_FALSE(TrackPositionAt(t, 5, 0.1).has_value());
}

TEST(MarkerPlayback, CameraFrameTracksNeedThePose) {
  const auto dir = test::TempDir();
  WriteTrajectoriesCsv(TwoFrames(), dir / "tracks.csv");
  try {
    ReadTracksInWorld(dir / "tracks.csv", std::nullopt);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("--camera-pose"));
  }
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(1, 2, 3);
  const Trajectories world = ReadTracksInWorld(dir / "tracks.csv", pose);
  EXPECT_TRUE(world.tracks[0].positions[0].isApprox(Eigen::Vector3d(1, 2, 4)));
}

TEST(MarkerPlayback, ASimulatedRunPlayedBackAgainstItselfHasNoError) {
  const Tree tree = test::ViewerTree();
  const auto dir = test::TempDir();
  dynamics::SimulationOptions options;
  options.duration_s = 2.0;
  options.fps = 30;
  dynamics::PullSchedule pull;
  pull.rope = {.branch = 3, .arc_length = -1, .anchor = {1, 0, 0}, .force_n = 20};
  pull.hold_s = 0.3;
  pull.release_s = 0.8;
  options.pull = pull;
  const auto markers = dynamics::AutoMarkers(tree, 2, pull.rope);
  dynamics::MarkerTrackWriter writer(markers, dir / "markers.csv", dir / "markers.json");
  dynamics::FrameRecorder* recorders[] = {&writer};
  dynamics::RunSimulation(tree, options, recorders);
  const Trajectories measured = ReadTracksInWorld(dir / "markers.csv", std::nullopt);

  // The viewer's stepping with the same pull: frame for frame the same motion.
  dynamics::TreeDynamics sim(tree, options.dynamics);
  dynamics::LivePull live(sim, pull);
  double worst = 0.0, moved = 0.0;
  for (int frame = 1; frame <= 60; ++frame) {
    dynamics::AdvanceFrame(sim, live, 1.0 / 30);
    const MarkerComparison c = CompareMarkers(measured, markers, sim);
    ASSERT_EQ(c.markers.size(), markers.size()) << "frame " << frame;
    worst = std::max(worst, c.max_error_m);
    moved = std::max(moved, (c.markers.back().measured - markers.back().position).norm());
  }
  EXPECT_GT(moved, 0.01);  // the pulled point did move
  EXPECT_LT(worst, 2e-6);  // and the playback follows it to the written precision
  // A different material drifts away from the measurement.
  dynamics::TreeDynamics other(tree, options.dynamics);
  Material stiffer = other.material(3);
  stiffer.SetStiffness(stiffer.stiffness * 4);
  other.SetMaterial(3, stiffer);
  dynamics::LivePull other_pull(other, pull);
  for (int frame = 1; frame <= 20; ++frame) dynamics::AdvanceFrame(other, other_pull, 1.0 / 30);
  EXPECT_GT(CompareMarkers(measured, markers, other).rms_error_m, 1e-3);
}

}  // namespace
}  // namespace simtree::viewer
