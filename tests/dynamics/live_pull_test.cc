// A pull played frame by frame on a live simulation moves the tree exactly as RunSimulation does.

#include "simtree/dynamics/live_pull.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "dynamics/dynamics_fixtures.h"

namespace simtree::dynamics {
namespace {

TEST(LivePull, SplitFrameKeepsStepsUnderTheMaximum) {
  const FrameSplit a = SplitFrame(1.0 / 30, 0.01);
  EXPECT_EQ(a.steps, 4);
  EXPECT_DOUBLE_EQ(a.dt, 1.0 / 120);
  const FrameSplit b = SplitFrame(0.01, 0.05);
  EXPECT_EQ(b.steps, 1);
  EXPECT_DOUBLE_EQ(b.dt, 0.01);
  EXPECT_DOUBLE_EQ(AutomaticMaxStep(test::ThreeLevelTree()), 1.0 / (20 * 2.0));
}

// Records every frame's node positions.
class NodeCopies : public FrameRecorder {
 public:
  void Record(int, double, const TreeDynamics& sim) override {
    frames.emplace_back(sim.node_positions().begin(), sim.node_positions().end());
  }
  std::vector<std::vector<Eigen::Vector3f>> frames;
};

TEST(LivePull, AdvanceFrameMovesTheTreeAsRunSimulationDoes) {
  const Tree tree = test::ThreeLevelTree();
  SimulationOptions options;
  options.duration_s = 1.5;
  options.fps = 30;
  PullSchedule pull;
  pull.rope = {.branch = 2, .arc_length = -1, .anchor = {0, 3, 0}, .force_n = 25};
  pull.hold_s = 0.4;
  pull.release_s = 0.9;
  options.pull = pull;
  NodeCopies run;
  FrameRecorder* recorders[] = {&run};
  RunSimulation(tree, options, recorders);

  TreeDynamics sim(tree);
  LivePull live(sim, pull);
  ASSERT_TRUE(live.active());
  for (size_t frame = 1; frame < run.frames.size(); ++frame) {
    AdvanceFrame(sim, live, 1.0 / options.fps);
    const auto now = sim.node_positions();
    ASSERT_TRUE(std::equal(now.begin(), now.end(), run.frames[frame].begin())) << frame;
  }
}

}  // namespace
}  // namespace simtree::dynamics
