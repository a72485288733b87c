#include "simtree/dynamics/simulate.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <fstream>
#include <sstream>

#include "dynamics/dynamics_fixtures.h"
#include "simtree/core/error.h"
#include "simtree/dynamics/recorders.h"
#include "test_util.h"

namespace simtree::dynamics {
namespace {

PullSchedule PullTwig(const Tree& tree) {
  PullSchedule p;
  p.rope.branch = 1;
  p.rope.anchor = tree.branches[1].tip().position + Eigen::Vector3d(0, 0, -3);
  p.rope.force_n = 60;
  p.hold_s = 0.5;
  p.release_s = 1.0;
  return p;
}

TEST(PullSchedule, RampsHoldsAndReleases) {
  PullSchedule p;
  p.hold_s = 2.0;
  p.release_s = 5.0;
  EXPECT_EQ(p.Factor(0.0), 0.0);
  EXPECT_NEAR(p.Factor(1.0), 0.5, 1e-12);
  EXPECT_GT(p.Factor(1.5), p.Factor(1.0));
  EXPECT_EQ(p.Factor(2.0), 1.0);
  EXPECT_EQ(p.Factor(4.99), 1.0);
  EXPECT_EQ(p.Factor(5.0), 0.0);
  p.hold_s = 0.0;
  EXPECT_EQ(p.Factor(0.0), 1.0);
  EXPECT_EQ(FrameCount(10.0, 30.0), 301);
  EXPECT_EQ(FrameCount(0.0, 30.0), 1);
}

TEST(Simulation, WritesNodeFramesMarkersAndAnimation) {
  const auto dir = test::TempDir();
  const Tree tree = test::ThreeLevelTree();
  SimulationOptions options;
  options.duration_s = 2.0;
  options.fps = 25;
  options.pull = PullTwig(tree);
  const std::vector<Marker> markers = AutoMarkers(tree, 1, options.pull->rope);
  ASSERT_EQ(markers.size(), 4u);  // tips of branches 0, 1, 3 and the pulled point
  NodeFrameWriter nodes(dir / "nodes.bin");
  MarkerTrackWriter tracks(markers, dir / "markers.csv", dir / "markers.json");
  AnimationRecorder animation(dir / "animation.glb", markers);
  std::vector<FrameRecorder*> recorders = {&nodes, &tracks, &animation};
  const SimulationResult result = RunSimulation(tree, options, recorders);
  EXPECT_EQ(result.frames, 51);
  EXPECT_NEAR(result.pull_tension_n, 60.0, 1e-12);
  EXPECT_GT(result.steps, 50);
  EXPECT_LE(result.time_step_s, 1.0 / (20 * 2.0) + 1e-12);

  const NodeFrames frames = ReadNodeFrames(dir / "nodes.bin");
  EXPECT_EQ(frames.frame_count, 51);
  EXPECT_EQ(frames.node_count, tree.NodeCount());
  EXPECT_EQ(frames.fps, 25.0);
  ASSERT_EQ(frames.branch_first_node.size(), 4u);
  EXPECT_EQ(frames.branch_node_count[2], 7u);
  // Frame 0 is the rest pose; the pulled tip has moved by the end of the hold.
  const int tip1 = frames.branch_first_node[1] + frames.branch_node_count[1] - 1;
  EXPECT_NEAR(frames.xyz[3 * tip1 + 2], tree.branches[1].tip().position.z(), 1e-6);
  const int hold_frame = 25;  // 1.0 s
  const float z_held = frames.xyz[3 * (hold_frame * frames.node_count + tip1) + 2];
  EXPECT_LT(z_held, tree.branches[1].tip().position.z() - 0.005);

  // The CSV: comment, header, one row per (frame, marker), world frame.
  std::ifstream csv(dir / "markers.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "# simtree.trajectories v1 frame=world units=m");
  std::getline(csv, line);
  EXPECT_EQ(line, "frame,time_s,marker,x,y,z,valid");
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 51 * 4);
  const std::string json = test::ReadText(dir / "markers.json");
  EXPECT_NE(json.find("\"simtree.markers\""), std::string::npos);
  EXPECT_NE(json.find("\"pull\""), std::string::npos);

  // The animation: one joint per node, 51 keys per track.
  EXPECT_EQ(animation.joint_count(), tree.NodeCount());
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, (dir / "animation.glb").string()))
      << err;
  EXPECT_EQ(model.skins[0].joints.size(), static_cast<size_t>(tree.NodeCount()));
  EXPECT_EQ(model.animations[0].channels.size(), 2u * tree.NodeCount() + markers.size());
  EXPECT_EQ(model.accessors[model.animations[0].samplers[0].input].count, 51u);
}

TEST(Simulation, FewerJointsBlendBetweenNodes) {
  const auto dir = test::TempDir();
  const Tree tree = test::ThreeLevelTree();
  SimulationOptions options;
  options.duration_s = 0.2;
  AnimationOptions few;
  few.max_joints = 30;
  AnimationRecorder animation(dir / "a.gltf", {}, few);
  std::vector<FrameRecorder*> recorders = {&animation};
  RunSimulation(tree, options, recorders);
  EXPECT_LE(animation.joint_count(), 30);
  EXPECT_GE(animation.joint_count(), 2 * tree.size());  // at least base and tip of each branch
  EXPECT_TRUE(std::filesystem::exists(dir / "a.gltf"));
}

TEST(Simulation, ReadNodeFramesRefusesDamagedFiles) {
  const auto dir = test::TempDir();
  const Tree tree = test::ThreeLevelTree();
  SimulationOptions options;
  options.duration_s = 0.1;
  NodeFrameWriter nodes(dir / "nodes.bin");
  std::vector<FrameRecorder*> recorders = {&nodes};
  RunSimulation(tree, options, recorders);
  std::string bytes = test::ReadText(dir / "nodes.bin");
  test::WriteText(dir / "short.bin", bytes.substr(0, bytes.size() - 5));
  EXPECT_THROW(ReadNodeFrames(dir / "short.bin"), InputError);
  bytes[0] = 'X';
  test::WriteText(dir / "magic.bin", bytes);
  EXPECT_THROW(ReadNodeFrames(dir / "magic.bin"), InputError);
}

TEST(Simulation, BadOptionsAreRefusedBeforeAnyOutput) {
  const auto dir = test::TempDir();
  const Tree tree = test::ThreeLevelTree();
  auto run = [&](SimulationOptions options) {
    NodeFrameWriter nodes(dir / "nodes.bin");
    std::vector<FrameRecorder*> recorders = {&nodes};
    EXPECT_THROW(RunSimulation(tree, options, recorders), InputError);
    EXPECT_TRUE(std::filesystem::is_empty(dir));
  };
  SimulationOptions o;
  o.duration_s = -1;
  run(o);
  o = {};
  o.fps = 0;
  run(o);
  o = {};
  o.duration_s = NAN;
  run(o);
  o = {};
  o.pull = PullTwig(tree);
  o.pull->hold_s = -0.5;
  run(o);
  o.pull = PullTwig(tree);
  o.pull->release_s = 0.1;  // before the hold
  run(o);
  o.pull = PullTwig(tree);
  o.pull->rope.branch = 42;
  run(o);
  o.pull = PullTwig(tree);
  o.pull->rope.force_n = -3;
  run(o);
  Tree nan_tree = tree;
  nan_tree.branches[0].material->modes[2].frequency_hz = NAN;
  NodeFrameWriter nodes(dir / "nodes.bin");
  std::vector<FrameRecorder*> recorders = {&nodes};
  EXPECT_THROW(RunSimulation(nan_tree, SimulationOptions{}, recorders), InputError);
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(SimulationOptions, ValidateNamesTheBadField) {
  const Tree tree = test::ThreeLevelTree();
  EXPECT_NO_THROW(SimulationOptions{}.Validate());
  const auto field = [&](auto change) {
    SimulationOptions o;
    o.pull = PullTwig(tree);
    change(o);
    return test::InputErrorField([&] { o.Validate(); });
  };
  EXPECT_EQ(field([](SimulationOptions& o) { o.duration_s = -2; }), "duration_s");
  EXPECT_EQ(field([](SimulationOptions& o) { o.duration_s = 1e9; }), "duration_s");
  EXPECT_EQ(field([](SimulationOptions& o) { o.fps = 0; }), "fps");
  EXPECT_EQ(field([](SimulationOptions& o) { o.max_time_step_s = NAN; }), "max_time_step_s");
  EXPECT_EQ(field([](SimulationOptions& o) { o.pull->hold_s = -1; }), "hold_s");
  EXPECT_EQ(field([](SimulationOptions& o) { o.pull->release_s = 0.2; }), "release_s");
  EXPECT_EQ(field([](SimulationOptions& o) { o.dynamics.max_threads = -1; }), "max_threads");
  EXPECT_EQ(field([](SimulationOptions& o) { o.dynamics.wind.modes = 0; }), "modes");
}

TEST(AnimationOptions, ValidateNamesTheBadField) {
  EXPECT_NO_THROW(AnimationOptions{}.Validate());
  const auto field = [&](auto change) {
    AnimationOptions o;
    change(o);
    return test::InputErrorField([&] { o.Validate(); });
  };
  EXPECT_EQ(field([](AnimationOptions& o) { o.mesh.sides = 2; }), "mesh.sides");
  EXPECT_EQ(field([](AnimationOptions& o) { o.mesh.min_radius = -1e-3; }), "mesh.min_radius");
  EXPECT_EQ(field([](AnimationOptions& o) { o.max_joints = 0; }), "max_joints");
  EXPECT_EQ(field([](AnimationOptions& o) { o.max_keys = 0; }), "max_keys");
  // The recorder refuses them when it is made, before a run.
  EXPECT_THROW(AnimationRecorder("a.glb", {}, {.max_joints = -4}), InputError);
}

}  // namespace
}  // namespace simtree::dynamics
