// `simtree reconstruct` end to end on a real scan, and its bad inputs.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/tree_json.h"
#include "test_util.h"

namespace simtree::reconstruction {
namespace {

using ::testing::HasSubstr;

TEST(ReconstructCli, WritesTreeMeshAndPicture) {
  const auto dir = test::TempDir();
  const std::string scan = test::SharedData("real-scans/rtwig_cloud.xyz").string();
  const auto r =
      test::RunCli("-q reconstruct " + scan + " --out " + (dir / "t.json").string() + " --mesh " +
                   (dir / "t.ply").string() + " --picture " + (dir / "t.png").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("trunk: MSAC cylinder radius"));
  EXPECT_THAT(r.output, HasSubstr("within 2 cm"));
  const Tree tree = ReadTreeJson(dir / "t.json");
  EXPECT_GT(tree.size(), 10);
  EXPECT_EQ(tree.metadata.source, "reconstructed from rtwig_cloud.xyz");
  EXPECT_GT(std::filesystem::file_size(dir / "t.ply"), 1000u);
  EXPECT_GT(std::filesystem::file_size(dir / "t.png"), 1000u);
}

TEST(ReconstructCli, BadInputsSayWhatIsWrongAndWriteNothing) {
  const auto dir = test::TempDir();
  const auto out = (dir / "t.json").string();
  test::WriteText(dir / "empty.xyz", "");
  auto r = test::RunCli("reconstruct " + (dir / "empty.xyz").string() + " --out " + out);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("empty.xyz"));
  std::string millimetres;
  for (int i = 0; i < 400; ++i) {
    millimetres += std::to_string(30.0 * std::cos(i)) + " " + std::to_string(30.0 * std::sin(i)) +
                   " " + std::to_string(5.0 * i) + "\n";
  }
  test::WriteText(dir / "mm.xyz", millimetres);
  r = test::RunCli("reconstruct " + (dir / "mm.xyz").string() + " --out " + out);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("looks like millimetres"));
  EXPECT_THAT(r.output, HasSubstr("--scale 0.001"));
  EXPECT_FALSE(std::filesystem::exists(out));
  // With the scale it reads.
  r = test::RunCli("-q reconstruct " + (dir / "mm.xyz").string() + " --scale 0.001 --out " + out);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  // Never over its input.
  r = test::RunCli("reconstruct " + (dir / "mm.xyz").string() + " --out " +
                   (dir / "mm.xyz").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(std::filesystem::exists(dir / "mm.xyz"));
}

// Outputs that cannot be written (a mesh extension it does not take, a folder where the picture
// goes) are refused by their names before the reconstruction, and leave the older tree as it was
// and no temporary behind (AtomicFileSet's tests: a failure while writing commits none).
TEST(ReconstructCli, OutputsThatCannotBeWrittenAreRefusedFirst) {
  const auto dir = test::TempDir();
  const std::string scan = test::SharedData("real-scans/rtwig_cloud.xyz").string();
  const auto out = dir / "t.json";
  test::WriteText(out, "older");
  auto r = test::RunCli("reconstruct " + scan + " --out " + out.string() + " --mesh " +
                        (dir / "t.stl").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("t.stl: expected a mesh file ending in .ply or .obj"));
  EXPECT_THAT(r.output, ::testing::Not(HasSubstr("trunk:")));
  EXPECT_EQ(test::ReadText(out), "older");
  r = test::RunCli("reconstruct " + scan + " --out " + (dir / "t.yaml").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("t.yaml: expected a tree file ending in .json"));
  EXPECT_THAT(r.output, ::testing::Not(HasSubstr("trunk:")));
  std::filesystem::create_directories(dir / "picture.png");
  r = test::RunCli("reconstruct " + scan + " --out " + out.string() + " --picture " +
                   (dir / "picture.png").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("picture.png: is a folder"));
  EXPECT_THAT(r.output, ::testing::Not(HasSubstr("trunk:")));
  EXPECT_EQ(test::ReadText(out), "older");
  std::vector<std::string> left;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    left.push_back(entry.path().filename().string());
  }
  EXPECT_THAT(left, ::testing::UnorderedElementsAre("t.json", "picture.png"));
}

}  // namespace
}  // namespace simtree::reconstruction
