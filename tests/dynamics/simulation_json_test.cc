#include "simtree/dynamics/simulation_json.h"

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "dynamics/dynamics_fixtures.h"
#include "test_util.h"

namespace simtree::dynamics {
namespace {

// The top-level keys of a simulation.json file, in file order.
std::vector<std::string> KeysOf(const nlohmann::ordered_json& doc) {
  std::vector<std::string> keys;
  for (const auto& item : doc.items()) keys.push_back(item.key());
  return keys;
}

// A pull at the tip of the three-level tree's trunk, as `simtree simulate --pull 0` asks.
SimulationJsonContent PulledTrunk(const Tree& tree) {
  SimulationOptions sim;
  sim.duration_s = 2.0;
  sim.fps = 25.0;
  PullSchedule pull;
  pull.rope.branch = 0;
  pull.rope.anchor = Eigen::Vector3d(5, 0, 0);
  pull.rope.force_n = 40.0;
  sim.pull = pull;
  SimulationResult result;
  result.frames = 51;
  result.steps = 400;
  result.time_step_s = 0.005;
  result.pull_tension_n = 40.0;
  result.pull_point = Eigen::Vector3d(0, 0, 3);
  SimulationJsonContent content = DescribeSimulation(tree, sim, result);
  content.tree_file = "tree.json";
  content.markers = 3;
  content.outputs = {"nodes.bin", "simulation.json"};
  return content;
}

TEST(SimulationJson, WritesTheKeysInOrderAndReadsBack) {
  const Tree tree = test::ThreeLevelTree();
  const std::filesystem::path path = test::TempDir() / "simulation.json";
  WriteSimulationJson(PulledTrunk(tree), path);
  const std::string text = test::ReadText(path);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  const auto doc = nlohmann::ordered_json::parse(text);
  EXPECT_EQ(KeysOf(doc),
            (std::vector<std::string>{"format", "version", "tree", "branches", "nodes",
                                      "duration_s", "fps", "frames", "time_step_s", "steps",
                                      "integrator", "base_excitation", "transfer_loads", "gravity",
                                      "demo_mode_spread", "pull", "wind", "markers", "outputs"}));
  EXPECT_EQ(doc["format"], "simtree.simulation");
  EXPECT_EQ(doc["version"], 1);
  EXPECT_EQ(doc["tree"], "tree.json");
  EXPECT_EQ(doc["branches"], tree.size());
  EXPECT_EQ(doc["nodes"], tree.NodeCount());
  EXPECT_EQ(doc["frames"], 51);
  EXPECT_TRUE(doc["wind"].is_null());
  EXPECT_EQ(doc["outputs"], nlohmann::ordered_json({"nodes.bin", "simulation.json"}));
  // The tip (arc length -1) is written as the trunk's length.
  EXPECT_DOUBLE_EQ(doc["pull"]["arc_length_m"].get<double>(), tree.branches[0].Length());
  EXPECT_EQ(doc["pull"]["mode"], "force");
  EXPECT_EQ(doc["pull"]["point"], nlohmann::ordered_json({0.0, 0.0, 3.0}));
}

TEST(SimulationJson, OptionalKeysFollowTheContent) {
  const Tree tree = test::ThreeLevelTree();
  SimulationJsonContent content = PulledTrunk(tree);
  content.material_file = "tree_parameters.txt";
  content.record_model = false;
  content.pull_fit = {{"force", {1.0, 2.0, 3.0}}, {"markers", 4}};
  content.options.dynamics.wind.enabled = true;
  content.wind_heading_deg = 90.0;
  const auto doc = SimulationJson(content);
  EXPECT_EQ(doc["material_file"], "tree_parameters.txt");
  EXPECT_FALSE(doc.contains("integrator"));
  EXPECT_FALSE(doc.contains("demo_mode_spread"));
  const std::vector<std::string> keys = KeysOf(doc);
  const auto pull = std::find(keys.begin(), keys.end(), "pull");
  ASSERT_NE(pull, keys.end());
  ASSERT_NE(pull + 1, keys.end());
  EXPECT_EQ(*(pull + 1), "pull_fit");
  EXPECT_EQ(doc["pull_fit"]["force"], nlohmann::ordered_json({1.0, 2.0, 3.0}));
  EXPECT_EQ(doc["pull_fit"]["markers"], 4);
  EXPECT_EQ(doc["wind"]["heading_deg"], 90.0);
  content.options.pull.reset();
  EXPECT_TRUE(SimulationJson(content)["pull"].is_null());
}

TEST(SimulationJson, AFolderThatCannotBeMadeIsAnIoError) {
  const Tree tree = test::ThreeLevelTree();
  const std::filesystem::path file = test::TempDir() / "a_file";
  test::WriteText(file, "not a folder\n");
  EXPECT_THROW(WriteSimulationJson(PulledTrunk(tree), file / "simulation.json"), IoError);
}

}  // namespace
}  // namespace simtree::dynamics
