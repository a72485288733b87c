#include "simtree/core/legacy_format.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/core/units.h"
#include "test_util.h"

namespace simtree {
namespace {

using ::testing::HasSubstr;

std::filesystem::path Demo(const std::string& file) {
  return test::SharedData("authors-demo/" + file);
}

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(LegacyFormat, ReadsBothDemoTreesWithChildrenOnTheirParents) {
  for (const auto& [file, count] : {std::pair{"tree01.txt", 95}, std::pair{"tree02.txt", 148}}) {
    const Tree tree = ReadLegacyTree(Demo(std::string("tree_model/") + file));
    EXPECT_EQ(tree.size(), count) << file;
    for (const Branch& b : tree.branches) {
      if (b.is_trunk()) continue;
      const Node& on = tree.branches[b.parent].nodes[b.parent_node];
      EXPECT_EQ(b.base().position, on.position) << file << " branch " << b.id;
    }
    // Z up after conversion, 2-5 m tall at the default scale.
    Eigen::Vector3d lo, hi;
    tree.Bounds(&lo, &hi);
    EXPECT_GT(hi.z() - tree.trunk().base().position.z(), 2.0);
    EXPECT_LT(hi.z() - tree.trunk().base().position.z(), 5.0);
    // The demo's trunks start straight up its Y axis: +Z here.
    const Eigen::Vector3d first = tree.trunk().nodes[1].position - tree.trunk().nodes[0].position;
    EXPECT_TRUE(first.normalized().isApprox(Eigen::Vector3d::UnitZ()));
  }
}

TEST(LegacyFormat, LevelsMatchTheDemoColours) {
  // The demo colours branches by level; a round trip writes the same words back.
  const Tree tree = ReadLegacyTree(Demo("tree_model/tree02.txt"));
  EXPECT_EQ(tree.MaxLevel(), 5);
  EXPECT_EQ(LegacyLevelColour(0), "red");
  EXPECT_EQ(LegacyLevelColour(5), "orange");
}

TEST(LegacyFormat, RoundTripIsByteExact) {
  const auto dir = test::TempDir();
  for (const char* file : {"tree01.txt", "tree02.txt"}) {
    const Tree tree = ReadLegacyTree(Demo(std::string("tree_model/") + file));
    WriteLegacyTree(tree, dir / file);
    EXPECT_EQ(test::ReadText(dir / file), test::ReadText(Demo(std::string("tree_model/") + file)))
        << file;
  }
  Tree tree = ReadLegacyTree(Demo("tree_model/tree01.txt"));
  ReadLegacyParameters(Demo("tree_parameters.txt"), tree);
  WriteLegacyParameters(tree, dir / "params.txt");
  EXPECT_EQ(test::ReadText(dir / "params.txt"), test::ReadText(Demo("tree_parameters.txt")));
}

TEST(LegacyFormat, ParametersBecomeMaterials) {
  Tree tree = ReadLegacyTree(Demo("tree_model/tree01.txt"));
  ReadLegacyParameters(Demo("tree_parameters.txt"), tree);
  ASSERT_TRUE(tree.IsSimulationReady());
  const Material& trunk = *tree.trunk().material;
  EXPECT_EQ(trunk.modes[0].frequency_hz, 3.0);
  EXPECT_EQ(trunk.modes[2].damping_ratio, 0.02);
  EXPECT_EQ(trunk.stiffness, 30000.0);
  EXPECT_NEAR(trunk.mass_kg, 30000.0 / (4 * kPi * kPi * 9.0), 1e-9);
}

TEST(LegacyFormat, ScaleAndAxes) {
  LegacyOptions o;
  o.scale = 1.0;
  o.y_up = false;
  const Tree raw = ReadLegacyTree(Demo("tree_model/tree01.txt"), o);
  const Tree z_up = ReadLegacyTree(Demo("tree_model/tree01.txt"));
  const Eigen::Vector3d p = raw.branches[5].nodes[3].position;
  EXPECT_TRUE(
      z_up.branches[5].nodes[3].position.isApprox(0.25 * Eigen::Vector3d(p.x(), -p.z(), p.y())));
  EXPECT_EQ(z_up.branches[5].nodes[3].radius, 0.25 * raw.branches[5].nodes[3].radius);
}

class LegacyBadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::TempDir();
    original_ = test::ReadText(Demo("tree_model/tree01.txt"));
  }
  std::string ReadError(const std::string& text) {
    test::WriteText(dir_ / "bad.txt", text);
    return ErrorOf([&] { ReadLegacyTree(dir_ / "bad.txt"); });
  }
  std::filesystem::path dir_;
  std::string original_;
};

TEST_F(LegacyBadInput, TruncatedFile) {
  const std::string text = original_.substr(0, original_.size() - 200);
  const std::string error = ReadError(text);
  EXPECT_THAT(error, HasSubstr("bad.txt: line "));
  EXPECT_THAT(error, HasSubstr("of branch 94"));
}

TEST_F(LegacyBadInput, ChildIndexOutOfRange) {
  std::string text = original_;
  text.replace(text.find("1 15\r\n"), 6, "1 99\r\n");
  EXPECT_THAT(
      ReadError(text),
      HasSubstr("bad.txt: line 3: child 1 of branch 0 starts at node 99, but branch 0 has 83 nodes "
                "(expected an index in [0, 82])"));
}

TEST_F(LegacyBadInput, ChildIdOutOfRangeHeaderAndNumbers) {
  std::string text = original_;
  text.replace(text.find("1 15\r\n"), 6, "400 15\r\n");
  EXPECT_THAT(ReadError(text), HasSubstr("line 3: child id 400 of branch 0 is out of range"));
  EXPECT_THAT(ReadError("Rows=3\r\n"), HasSubstr("line 1: expected the header"));
  EXPECT_THAT(ReadError(""), HasSubstr("line 1: expected the header \"RowMax=<branches>\", got "
                                       "the end of the file"));
  text = original_;
  text.replace(text.find("0.725534"), 8, "nan");
  EXPECT_THAT(ReadError(text), HasSubstr("line 22: expected a finite number for the radius"));
}

TEST_F(LegacyBadInput, ParameterFileTooShortOrMalformed) {
  Tree tree = ReadLegacyTree(Demo("tree_model/tree01.txt"));
  std::string params = test::ReadText(Demo("tree_parameters.txt"));
  // Keep the count line and 48 branch lines.
  size_t cut = 0;
  for (int i = 0; i < 49; ++i) cut = params.find('\n', cut) + 1;
  test::WriteText(dir_ / "p.txt", params.substr(0, cut));
  EXPECT_THAT(ErrorOf([&] { ReadLegacyParameters(dir_ / "p.txt", tree); }),
              HasSubstr("p.txt: line 50: expected 95 parameter lines (one per branch) but the "
                        "file has 48"));
  EXPECT_FALSE(tree.IsSimulationReady());  // nothing half-applied
  test::WriteText(dir_ / "p.txt", "2\r\n1 0.02 100\r\n1 0.02 100\r\n");
  EXPECT_THAT(ErrorOf([&] { ReadLegacyParameters(dir_ / "p.txt", tree); }),
              HasSubstr("expected parameters for 95 branches (the tree's), got 2"));
  test::WriteText(dir_ / "p.txt", "1\r\n0 0.02 100\r\n");
  EXPECT_THAT(ErrorOf([&] { ParseLegacyParameters(test::ReadText(dir_ / "p.txt"), "p.txt"); }),
              HasSubstr("p.txt: line 2: expected a positive frequency, got 0"));
}

}  // namespace
}  // namespace simtree
