#include "simtree/pipeline/detail/pull_fit.h"

#include <gtest/gtest.h>

#include "dynamics/dynamics_fixtures.h"
#include "simtree/core/error.h"
#include "simtree/dynamics/simulate.h"
#include "simtree/dynamics/tree_dynamics.h"

using namespace simtree;
using simtree::pipeline::detail::FitPull;
using simtree::pipeline::detail::PullFit;

namespace {

struct Scene {
  Tree tree;
  Trajectories tracks;
  Eigen::Isometry3d world_from_camera = Eigen::Isometry3d::Identity();
};

// ThreeLevelTree with four markers, pulled by `force` at `arc` on branch 1: rest until 0.5 s,
// a linear ramp to full at 1 s, held until the release at 2 s, 30 frames a second (camera frame).
Scene PulledScene(const Eigen::Vector3d& force, double arc) {
  Scene s;
  s.tree = test::ThreeLevelTree();
  const std::pair<int, double> at[] = {{0, 2.0}, {1, 0.75}, {2, 0.5}, {3, 0.6}};
  for (int i = 0; i < 4; ++i) {
    Marker m;
    m.id = i;
    m.branch = at[i].first;
    m.arc_length = at[i].second;
    m.parent = i == 0 ? -1 : 0;
    m.position = s.tree.branches[m.branch].PointAt(m.arc_length);
    s.tree.markers.push_back(m);
  }
  dynamics::TreeDynamics sim(s.tree);
  dynamics::Rope rope;
  rope.branch = 1;
  rope.arc_length = arc;
  rope.anchor = s.tree.branches[1].PointAt(arc) + 1000 * force.normalized();
  rope.force_n = force.norm();
  sim.AttachRope(rope);
  sim.SettleStatic();
  s.world_from_camera.linear() =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.2, 1, 0.3).normalized()).toRotationMatrix();
  s.world_from_camera.translation() = Eigen::Vector3d(0.5, -3, 1.2);
  const Eigen::Isometry3d camera_from_world = s.world_from_camera.inverse();
  for (const Marker& m : s.tree.markers) {
    MarkerTrack track;
    track.marker = m.id;
    s.tracks.tracks.push_back(track);
  }
  for (int f = 0; f <= 90; ++f) {
    const double t = f / 30.0;
    s.tracks.frames.push_back(f);
    s.tracks.times_s.push_back(t);
    const double share = t <= 0.5 ? 0.0 : t < 1.0 ? (t - 0.5) / 0.5 : t <= 2.0 ? 1.0 : 0.0;
    for (size_t i = 0; i < s.tree.markers.size(); ++i) {
      const Marker& m = s.tree.markers[i];
      const Eigen::Vector3d held = sim.PointPosition(m.branch, m.arc_length);
      const Eigen::Vector3d world = m.position + share * (held - m.position);
      s.tracks.tracks[i].positions.push_back(camera_from_world * world);
      s.tracks.tracks[i].valid.push_back(true);
    }
  }
  return s;
}

// Every marker's position (camera frame) at every frame of a simulation.
class CameraTracks : public dynamics::FrameRecorder {
 public:
  CameraTracks(const Tree& tree, const Eigen::Isometry3d& camera_from_world)
      : tree_(tree), camera_from_world_(camera_from_world) {
    for (const Marker& m : tree.markers) {
      MarkerTrack track;
      track.marker = m.id;
      tracks.tracks.push_back(track);
    }
  }
  void Record(int frame, double time_s, const dynamics::TreeDynamics& sim) override {
    tracks.frames.push_back(frame);
    tracks.times_s.push_back(time_s);
    for (size_t i = 0; i < tree_.markers.size(); ++i) {
      const Marker& m = tree_.markers[i];
      tracks.tracks[i].positions.push_back(camera_from_world_ *
                                           sim.PointPosition(m.branch, m.arc_length));
      tracks.tracks[i].valid.push_back(true);
    }
  }
  Trajectories tracks;

 private:
  const Tree& tree_;
  Eigen::Isometry3d camera_from_world_;
};

// The same tree pulled up to 2.5 s, let go at `release_s`, the markers tracked through the free
// motion, 30 frames a second.
Scene ReleasedScene(const Eigen::Vector3d& force, double arc, double release_s) {
  Scene s = PulledScene(force, arc);
  dynamics::SimulationOptions sim;
  sim.duration_s = release_s + 3.0;
  sim.fps = 30.0;
  sim.max_time_step_s = 1.0 / 300.0;  // the replay's step, which the fit simulates with
  dynamics::PullSchedule pull;
  pull.rope.branch = 1;
  pull.rope.arc_length = arc;
  pull.rope.anchor = s.tree.branches[1].PointAt(arc) + 1000 * force.normalized();
  pull.rope.force_n = force.norm();
  pull.hold_s = 2.5;  // a slow ramp leaves the tree still when it is held
  pull.release_s = release_s;
  sim.pull = pull;
  CameraTracks recorder(s.tree, s.world_from_camera.inverse());
  dynamics::FrameRecorder* recorders[] = {&recorder};
  dynamics::RunSimulation(s.tree, sim, recorders);
  s.tracks = recorder.tracks;
  return s;
}

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
