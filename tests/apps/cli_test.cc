// The CLI as a user meets it: exit codes, messages, and that bad input leaves no output behind.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_util.h"

namespace simtree {
namespace {

using ::testing::HasSubstr;

std::string Demo(const std::string& file) {
  return test::SharedData("authors-demo/" + file).string();
}

TEST(Cli, VersionAndHelp) {
  EXPECT_EQ(test::RunCli("--version").exit_code, 0);
  const auto help = test::RunCli("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_THAT(help.output, HasSubstr("convert"));
  for (const char* verb : {"convert", "mesh", "info"}) {
    const auto r = test::RunCli(std::string(verb) + " --help");
    EXPECT_EQ(r.exit_code, 0) << verb;
    EXPECT_THAT(r.output, HasSubstr("Examples:")) << verb;
  }
}

TEST(Cli, UnbuiltStageExitsTwoAndSaysSo) {
  // A verb that is still a placeholder; when every stage is built this test has nothing to test.
  const auto r = test::RunCli("--help");
  const size_t at = r.output.find("[not built yet]");
  if (at == std::string::npos) GTEST_SKIP() << "every stage is built";
  const size_t line = r.output.rfind('\n', at);
  std::string verb = r.output.substr(line + 1, at - line - 1);
  verb = verb.substr(verb.find_first_not_of(' '));
  verb = verb.substr(0, verb.find(' '));
  const auto run = test::RunCli(verb + " some-input --some-option 3");
  EXPECT_EQ(run.exit_code, 2) << verb;
  EXPECT_THAT(run.output, HasSubstr("not built yet"));
}

TEST(Cli, ConvertAndMeshTheAuthorsTree) {
  const auto dir = test::TempDir();
  const std::string json = (dir / "t.json").string();
  auto r = test::RunCli("-q convert " + Demo("tree_model/tree01.txt") + " " + json + " --params " +
                        Demo("tree_parameters.txt"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = test::RunCli("mesh " + json + " --out " + (dir / "t.ply").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "t.ply"));
  r = test::RunCli("info " + json);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("branches        95"));
  EXPECT_THAT(r.output, HasSubstr("frequency       1 - 3 Hz"));
}

// Each bad input: a non-zero exit, a message naming the file and place, and no output file.
struct BadInput {
  const char* name;
  const char* file_name;
  std::string content;
  std::string extra_args;
  std::string expected_message;
};

// Names the case in test output instead of dumping its bytes.
void PrintTo(const BadInput& bad, std::ostream* os) { *os << bad.name; }

class CliBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CliBadInput, FailsClearlyAndWritesNothing) {
  const BadInput& bad = GetParam();
  const auto dir = test::TempDir();
  const auto input = dir / bad.file_name;
  test::WriteText(input, bad.content);
  const auto output = dir / "out.json";
  const auto r =
      test::RunCli("convert " + input.string() + " " + output.string() + " " + bad.extra_args);
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr(bad.expected_message));
  EXPECT_THAT(r.output, HasSubstr(bad.file_name));
  EXPECT_FALSE(std::filesystem::exists(output));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);  // only the input
}

std::string Tree01() {
  return test::ReadText(test::SharedData("authors-demo/tree_model/tree01.txt"));
}

std::string SmallJson(const std::string& patch_from, const std::string& patch_to) {
  std::string doc = R"({"format": "simtree.tree", "version": 1, "branches": [
    {"id": 0, "parent": -1, "parent_node": 0, "level": 0,
     "nodes": [[0, 0, 0, 0.1], [0, 0, 1, 0.08]]}]})";
  doc.replace(doc.find(patch_from), patch_from.size(), patch_to);
  return doc;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CliBadInput,
    ::testing::Values(
        BadInput{
            "truncated_legacy", "tree.txt", Tree01().substr(0, 20000), "",
            "tree.txt: line 636: expected 4 numbers \"x y z radius\" for node 12 of branch 16"},
        BadInput{"child_out_of_range", "tree.txt",
                 [] {
                   std::string text = Tree01();
                   text.replace(text.find("1 15\r\n"), 6, "1 99\r\n");
                   return text;
                 }(),
                 "", "tree.txt: line 3: child 1 of branch 0 starts at node 99"},
        BadInput{"negative_radius", "tree.json", SmallJson("0.08]", "-0.08]"), "",
                 "tree.json: branches[0].nodes[1].radius: expected a positive radius, got -0.08"},
        BadInput{"nan", "tree.json", SmallJson("0.08]", "NaN]"), "", "tree.json: line 3"},
        BadInput{"wrong_version", "tree.json", SmallJson("\"version\": 1", "\"version\": 7"), "",
                 "tree.json: version: expected 1"},
        BadInput{"empty_json", "tree.json", "", "", "tree.json: line 1, column 1"},
        BadInput{"empty_legacy", "tree.txt", "", "", "tree.txt: line 1"}),
    [](const auto& case_info) { return std::string(case_info.param.name); });

TEST(Cli, ShortParameterFileNamesTheLine) {
  const auto dir = test::TempDir();
  std::string params = test::ReadText(test::SharedData("authors-demo/tree_parameters.txt"));
  size_t cut = 0;
  for (int i = 0; i < 11; ++i) cut = params.find('\n', cut) + 1;
  test::WriteText(dir / "params.txt", params.substr(0, cut));
  const auto r =
      test::RunCli("convert " + Demo("tree_model/tree01.txt") + " " + (dir / "out.json").string() +
                   " --params " + (dir / "params.txt").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("params.txt: line 12: expected 95 parameter lines"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out.json"));
}

TEST(Cli, AStaticTreeWithoutAPullTestBuildsWithAssumedMaterialsAndSimulates) {
  const auto dir = test::TempDir();
  const std::string tree = (dir / "static.json").string(), ready = (dir / "ready.json").string();
  // tree02 ships without a parameter file: a static tree, as a scan alone gives.
  auto r = test::RunCli("-q convert " + Demo("tree_model/tree02.txt") + " " + tree);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = test::RunCli("simulate " + tree + " --duration 0.1 --out " + (dir / "sim").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("simtree build --species"));
  r = test::RunCli("build " + tree + " --out " + ready);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("--materials: expected materials.json"));
  r = test::RunCli("build " + tree + " --species magnolia --out " + ready);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("no pull test"));
  r = test::RunCli("info " + ready);
  EXPECT_THAT(r.output, HasSubstr("0 measured, 0 interpolated, 0 default, "));
  EXPECT_THAT(r.output, HasSubstr("assumed values are typical of the kind of tree"));
  EXPECT_THAT(r.output, HasSubstr("frequency       0.955 - 0.955 Hz"));
  EXPECT_THAT(test::ReadText(ready), HasSubstr("\"assumed\""));
  r = test::RunCli("simulate " + ready + " --duration 0.1 --out " + (dir / "sim").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  // Bad values name the option and write nothing.
  for (const char* bad : {"1.2", "1.2,x", "0,0.03", "1.2,1.5"}) {
    const std::string out = (dir / "bad.json").string();
    r = test::RunCli("build " + tree + " --default-material " + bad + " --out " + out);
    EXPECT_NE(r.exit_code, 0) << bad;
    EXPECT_THAT(r.output, HasSubstr("--default-material")) << bad;
    EXPECT_FALSE(std::filesystem::exists(out)) << bad;
  }
  r = test::RunCli("build " + tree + " --species oak --out " + (dir / "oak.json").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("known species are acer_palmatum"));
}

TEST(Cli, NeverWritesOverItsInput) {
  const auto dir = test::TempDir();
  const auto json = dir / "t.json";
  ASSERT_EQ(
      test::RunCli("convert " + Demo("tree_model/tree01.txt") + " " + json.string()).exit_code, 0);
  const std::string before = test::ReadText(json);
  const auto r = test::RunCli("convert " + json.string() + " " + (dir / "./t.json").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("refusing to write over the input"));
  EXPECT_EQ(test::ReadText(json), before);
}

}  // namespace
}  // namespace simtree
