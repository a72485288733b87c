// `simtree view` and `simtree render` end to end: the real window under Xvfb (started by
// xvfb-run), driven by a script that pulls and releases a branch of the authors' tree01; a
// corrupt leaf texture still opens the viewer without leaves; `render` of tree02 writes frames
// that show the tree and a video.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/io/image_io.h"
#include "viewer_fixtures.h"

namespace simtree::viewer {
namespace {

using ::testing::HasSubstr;

constexpr int kPanel = 340;  // the viewer's side panel, left of the 3D view

// The scene part of a screenshot: pixels far from the sky are tree (the grid is thin and grey).
int TreePixels(const RgbImage& image) {
  int n = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = kPanel; x < image.width; ++x) {
      const int r = image.at(x, y, 0), g = image.at(x, y, 1), b = image.at(x, y, 2);
      if (std::abs(r - 199) + std::abs(g - 217) + std::abs(b - 235) > 150) ++n;
    }
  }
  return n;
}

int ChangedScenePixels(const RgbImage& a, const RgbImage& b) {
  int n = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = kPanel; x < a.width; ++x) {
      int d = 0;
      for (int c = 0; c < 3; ++c) d += std::abs(a.at(x, y, c) - b.at(x, y, c));
      n += d > 60;
    }
  }
  return n;
}

std::string Demo(const std::string& file) {
  return test::SharedData("authors-demo/" + file).string();
}

std::string UnderXvfb(const std::string& args) { return "-q view " + args; }

test::CliResult RunView(const std::string& args) {
  // xvfb-run is the CLI's caller here: the test needs no display of its own.
  const std::string command = std::string("xvfb-run -a -s \"-screen 0 1024x700x24\" \"") +
                              SIMTREE_CLI_PATH + "\" " + UnderXvfb(args);
  const std::filesystem::path log =
      std::filesystem::path(SIMTREE_TEST_TMP_DIR) / ("view-" + std::to_string(getpid()) + ".log");
  std::filesystem::create_directories(log.parent_path());
  const int status = std::system((command + " > \"" + log.string() + "\" 2>&1").c_str());
  test::CliResult result{WIFEXITED(status) ? WEXITSTATUS(status) : -1, test::ReadText(log)};
  std::filesystem::remove(log);
  return result;
}

TEST(ViewCli, ScriptedPullAndReleaseMoveTheTree) {
  const auto dir = test::TempDir();
  test::WriteText(dir / "pull.txt",
                  "wait 2\n"
                  "screenshot " +
                      (dir / "rest.png").string() +
                      "\n"
                      "pick-branch 1\n"
                      "drag-by 160 40 10\n"
                      "wait 10\n"
                      "screenshot " +
                      (dir / "pulled.png").string() +
                      "\n"
                      "release\n"
                      "wait 8\n"
                      "screenshot " +
                      (dir / "released.png").string() +
                      "\n"
                      "hover 5 5\n"
                      "quit\n");
  const auto r =
      RunView(Demo("tree_model/tree01.txt") + " --material-file " + Demo("tree_parameters.txt") +
              " --leaves none --size 1024,700 --script " + (dir / "pull.txt").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("grabbed branch 1 (level 1"));
  EXPECT_THAT(r.output, HasSubstr("released branch 1"));
  const RgbImage rest = ReadColorImage(dir / "rest.png");
  const RgbImage pulled = ReadColorImage(dir / "pulled.png");
  const RgbImage released = ReadColorImage(dir / "released.png");
  EXPECT_EQ(rest.width, 1024);
  EXPECT_EQ(rest.height, 700);
  // The tree is there, and it moved under the pull and again once let go.
  EXPECT_GT(TreePixels(rest), 5000);
  EXPECT_GT(ChangedScenePixels(rest, pulled), 500);
  EXPECT_GT(ChangedScenePixels(pulled, released), 500);
}

TEST(ViewCli, HoverTellsTheBranchAndItsMaterialSource) {
  const auto dir = test::TempDir();
  test::WriteText(dir / "hover.txt",
                  "pick-branch 0@1.0\n"
                  "release\n"
                  "material level 1 frequency 2.5\n"
                  "wait 1\n"
                  "quit\n");
  const auto r = RunView(Demo("tree_model/tree02.txt") +
                         " --leaves none --size 1024,700 --script " + (dir / "hover.txt").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("have no material: using the authors' demo values"));
  EXPECT_THAT(r.output, HasSubstr("grabbed branch 0 (level 0, parent -1): f 3 Hz"));
  EXPECT_THAT(r.output, HasSubstr("default"));
  EXPECT_THAT(r.output, HasSubstr("frequency = 2.5 on 14 branches"));
}

TEST(ViewCli, ACorruptLeafTextureStillOpensTheViewerWithoutLeaves) {
  const auto dir = test::TempDir();
  const auto leaves = test::CopyAppleLeaf(dir);
  test::WriteText(leaves / "leafup.bmp", "BM not really a bitmap");
  test::WriteText(dir / "shot.txt",
                  "wait 1\nscreenshot " + (dir / "bare.png").string() + "\nquit\n");
  const auto r = RunView(Demo("tree_model/tree01.txt") + " --leaves " + leaves.string() +
                         " --script " + (dir / "shot.txt").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("leafup.bmp"));
  EXPECT_THAT(r.output, HasSubstr("going on without leaves"));
  EXPECT_GT(TreePixels(ReadColorImage(dir / "bare.png")), 3000);
  // A broken leaf.txt too.
  std::filesystem::copy_file(test::AppleLeaf() / "leafup.bmp", leaves / "leafup.bmp",
                             std::filesystem::copy_options::overwrite_existing);
  test::WriteText(leaves / "leaf.txt", "PetioleVerNum=2 LeafVerNum=x\n");
  const auto r2 = RunView(Demo("tree_model/tree01.txt") + " --leaves " + leaves.string() +
                          " --script " + (dir / "shot.txt").string());
  ASSERT_EQ(r2.exit_code, 0) << r2.output;
  EXPECT_THAT(r2.output, HasSubstr("leaf.txt: line 1"));
}

TEST(ViewCli, BadInputIsAClearError) {
  const auto dir = test::TempDir();
  test::WriteText(dir / "bad.txt", "wait 1\nfly away\n");
  auto r = RunView(Demo("tree_model/tree01.txt") + " --script " + (dir / "bad.txt").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("bad.txt: line 2: unknown action \"fly\""));
  test::WriteText(dir / "pick.txt", "pick-branch 999\nquit\n");
  r = RunView(Demo("tree_model/tree01.txt") + " --script " + (dir / "pick.txt").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("expected a branch id in [0, 94], got 999"));
  r = RunView(Demo("tree_model/tree01.txt") + " --tracks " + Demo("tree_parameters.txt"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("tree_parameters.txt: line 1"));
}

TEST(RenderCli, Tree02FramesShowTheTreeAndBecomeAVideo) {
  const auto dir = test::TempDir();
  const auto r =
      test::RunCli("-q render " + Demo("tree_model/tree02.txt") +
                   " --pull 20 --force 300 --hold 0.3 --release 0.8 --duration 1.5 "
                   "--fps 10 --size 480,360 --out " +
                   (dir / "frames").string() + " --video " + (dir / "pull.mp4").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("leaves: "));
  const RgbImage first = ReadColorImage(dir / "frames" / "000000.png");
  EXPECT_EQ(first.width, 480);
  EXPECT_TRUE(std::filesystem::exists(dir / "frames" / "000015.png"));
  EXPECT_FALSE(std::filesystem::exists(dir / "frames" / "000016.png"));
  int tree = 0;
  for (int y = 0; y < first.height; ++y) {
    for (int x = 0; x < first.width; ++x) {
      tree += std::abs(first.at(x, y, 0) - 199) + std::abs(first.at(x, y, 2) - 235) > 120;
    }
  }
  EXPECT_GT(tree, 3000);
  EXPECT_GT(std::filesystem::file_size(dir / "pull.mp4"), 10000u);
  // An output folder that is an input is refused before anything is written.
  const auto bad = test::RunCli("-q render " + Demo("tree_model/tree02.txt") + " --out " +
                                test::SharedData("authors-demo/tree_model").string());
  EXPECT_NE(bad.exit_code, 0);
}

}  // namespace
}  // namespace simtree::viewer
