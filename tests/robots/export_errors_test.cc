// Trees the export refuses, with the branch and field named and no output written.

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "simtree/core/error.h"
#include "simtree/robots/export_robot.h"
#include "test_util.h"

namespace simtree::robots {
namespace {

Tree TwoBranches() {
  Tree tree;
  Branch trunk;
  trunk.nodes = {{Eigen::Vector3d(0, 0, 0), 0.05}, {Eigen::Vector3d(0, 0, 1), 0.03}};
  Branch child;
  child.id = 1;
  child.parent = 0;
  child.parent_node = 1;
  child.level = 1;
  child.nodes = {{Eigen::Vector3d(0, 0, 1), 0.02}, {Eigen::Vector3d(0.5, 0, 1.3), 0.01}};
  child.frame.v = Eigen::Vector3d(0.5, 0, 0.3).normalized();
  child.frame.u = Eigen::Vector3d::UnitZ().cross(child.frame.v).normalized();
  child.frame.w = child.frame.u.cross(child.frame.v);
  for (Branch* b : {&trunk, &child}) {
    b->material =
        Material::FromFrequencyDampingStiffness(1.5, 0.03, 100.0, MaterialSource::kDefault);
  }
  tree.branches = {trunk, child};
  return tree;
}

std::string ExportError(const Tree& tree, const std::filesystem::path& out) {
  return test::ErrorOf<InputError>([&] { ExportRobot(tree, {}, out, "t.json"); });
}

TEST(ExportErrors, GoodTreeExports) {
  const auto out = test::TempDir() / "tree.xml";
  const ExportResult result = ExportRobot(TwoBranches(), {}, out);
  EXPECT_EQ(result.bodies, 8);
  EXPECT_TRUE(std::filesystem::exists(out));
}

TEST(ExportErrors, TreeWithoutMaterialsIsRefused) {
  Tree tree = TwoBranches();
  tree.branches[1].material.reset();
  const auto out = test::TempDir() / "tree.xml";
  const std::string error = ExportError(tree, out);
  EXPECT_NE(error.find("t.json"), std::string::npos) << error;
  EXPECT_NE(error.find("branches[1]"), std::string::npos) << error;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(ExportErrors, ZeroRadiusIsRefused) {
  Tree tree = TwoBranches();
  tree.branches[1].nodes[1].radius = 0.0;
  const auto out = test::TempDir() / "tree.xml";
  const std::string error = ExportError(tree, out);
  EXPECT_NE(error.find("branches[1].nodes[1].radius"), std::string::npos) << error;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(ExportErrors, ZeroLengthIsRefused) {
  Tree tree = TwoBranches();
  tree.branches[1].nodes[1].position = tree.branches[1].nodes[0].position;
  const auto out = test::TempDir() / "tree.xml";
  const std::string error = ExportError(tree, out);
  EXPECT_NE(error.find("branches[1]"), std::string::npos) << error;
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(ExportErrors, BadOptionsAreRefusedByName) {
  ExportOptions options;
  options.model.segments_per_branch = 0;
  const std::string error = test::ErrorOf<InputError>(
      [&] { ExportRobot(TwoBranches(), options, test::TempDir() / "tree.xml"); });
  EXPECT_NE(error.find("model.segments_per_branch"), std::string::npos) << error;
}

TEST(ExportErrors, BudgetGivesLargeTreesFewerSegments) {
  ExportOptions options;
  options.model.segments_per_branch = 6;
  options.model.max_bodies = 6;
  const RobotModel model = MakeRobotModel(TwoBranches(), options);
  EXPECT_EQ(model.segments_per_branch, 3);
  EXPECT_EQ(model.segments.size(), 6u);
}

}  // namespace
}  // namespace simtree::robots
