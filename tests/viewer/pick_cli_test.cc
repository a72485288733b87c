// `simtree track --pick` end to end: the real picking window under Xvfb (xvfb-run), driven by a
// script through the window's own handlers (zoom, clicks on the tapes, a wrong click undone, a
// skip), writes the init.json the clicks say; escape writes nothing; without a display the verb
// refuses with a message and writes nothing.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "simtree/io/track_init.h"
#include "test_util.h"
#include "tracking/drawn_stream.h"

namespace fs = std::filesystem;

namespace simtree::viewer {
namespace {

using ::testing::HasSubstr;

// Three tapes; their true pixels in frame 0.
std::vector<Eigen::Vector2d> DrawThreeTapes(const fs::path& pull) {
  test::DrawnStream s;
  const std::vector<Eigen::Vector3d> points = {
      {-0.2, 0.0, 1.5}, {0.05, -0.1, 1.7}, {0.2, 0.15, 1.4}};
  s.positions = {points, points};
  test::WriteDrawnStream(s, pull);
  std::vector<Eigen::Vector2d> pixels;
  for (const Eigen::Vector3d& p : points) pixels.push_back(s.intrinsics.Project(p));
  return pixels;
}

std::string XvfbRun() { return "xvfb-run -a -s \"-screen 0 1024x768x24\" "; }

test::CliResult RunUnder(const std::string& prefix, const std::string& args) {
  const fs::path log = fs::path(SIMTREE_TEST_TMP_DIR) / ("pick-" + std::to_string(getpid()));
  fs::create_directories(log.parent_path());
  const int status = std::system(
      (prefix + "\"" + SIMTREE_CLI_PATH + "\" " + args + " > \"" + log.string() + "\" 2>&1")
          .c_str());
  test::CliResult r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, test::ReadText(log)};
  fs::remove(log);
  return r;
}

std::string PickArgs(const fs::path& dir) {
  return "-q track " + (dir / "pull").string() + " --pick --pick-script " +
         (dir / "pick.txt").string() + " --init-only --out " + (dir / "o").string();
}

TEST(PickCli, ScriptedClicksThroughTheWindowWriteInitJson) {
  const fs::path dir = test::TempDir();
  const std::vector<Eigen::Vector2d> truth = DrawThreeTapes(dir / "pull");
  // Zoomed in on the first tape, a click beside it taken back, then the tapes, one skipped.
  test::WriteText(dir / "pick.txt",
                  fmt::format("wait 2\nzoom 4 {0} {1}\nclick 5 5\nkey backspace\n"
                              "click-image {2} {3}\nzoom 0.25 {0} {1}\nkey s\n"
                              "click-image {4} {5}\nkey enter\n",
                              300, 300, truth[0].x(), truth[0].y(), truth[2].x(), truth[2].y()));
  const test::CliResult r = RunUnder(XvfbRun(), PickArgs(dir));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("picked 2 markers, skipped [1]"));
  const TrackInit init = ReadTrackInitJson(dir / "o" / "init.json");
  EXPECT_EQ(init.frame, 0);
  ASSERT_EQ(init.markers.size(), 2u);
  EXPECT_EQ(init.markers[0].id, 0);
  EXPECT_LT((init.markers[0].pixel - truth[0]).norm(), 1e-3);
  EXPECT_EQ(init.markers[1].id, 2);
  EXPECT_LT((init.markers[1].pixel - truth[2]).norm(), 1e-3);
}

TEST(PickCli, EscapeAndNoDisplayWriteNothing) {
  const fs::path dir = test::TempDir();
  DrawThreeTapes(dir / "pull");
  test::WriteText(dir / "pick.txt", "click-image 10 10\nkey escape\n");
  const test::CliResult cancelled = RunUnder(XvfbRun(), PickArgs(dir));
  EXPECT_NE(cancelled.exit_code, 0);
  EXPECT_THAT(cancelled.output, HasSubstr("cancelled: no init.json written"));
  EXPECT_FALSE(fs::exists(dir / "o" / "init.json"));

  const test::CliResult headless = RunUnder("env -u DISPLAY ", PickArgs(dir));
  EXPECT_NE(headless.exit_code, 0);
  EXPECT_THAT(headless.output, HasSubstr("no X display"));
  EXPECT_FALSE(fs::exists(dir / "o" / "init.json"));
}

}  // namespace
}  // namespace simtree::viewer
