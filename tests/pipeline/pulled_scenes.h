#pragma once
// Pulled and released test scenes for the pull fit: ThreeLevelTree with four markers, tracked
// in a camera frame.

#include <Eigen/Geometry>

#include "dynamics/dynamics_fixtures.h"
#include "simtree/core/tree.h"
#include "simtree/dynamics/simulate.h"
#include "simtree/dynamics/tree_dynamics.h"
#include "simtree/io/trajectories.h"
#include "simtree/pipeline/detail/branch_stiffness.h"

namespace simtree::test {

struct Scene {
  Tree tree;
  Trajectories tracks;
  Eigen::Isometry3d world_from_camera = Eigen::Isometry3d::Identity();
};

// ThreeLevelTree with four markers, pulled by `force` at `arc` on branch 1: rest until 0.5 s,
// a linear ramp to full at 1 s, held until the release at 2 s, 30 frames a second (camera frame).
inline Scene PulledScene(const Eigen::Vector3d& force, double arc) {
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
inline Scene ReleasedScene(const Eigen::Vector3d& force, double arc, double release_s,
                           double branch_stiffening = 1.0) {
  Scene s = PulledScene(force, arc);
  const Tree identified = s.tree;
  s.tree = pipeline::detail::StiffenBranches(s.tree, branch_stiffening);
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
  s.tree = identified;
  return s;
}

}  // namespace simtree::test
