#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/pipeline/run.h"
#include "simtree/pipeline/stage.h"
#include "test_util.h"

namespace fs = std::filesystem;
using namespace simtree::pipeline;

namespace {

// The message of the InputError `f` throws (empty when it throws none).
template <typename F>
std::string ErrorOf(F f) {
  try {
    f();
  } catch (const simtree::Error& e) {
    return e.what();
  }
  return "";
}

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(RunOptions, DefaultsAreValidAndBadValuesNameTheirField) {
  EXPECT_NO_THROW(RunOptions{}.Validate());
  RunOptions o;
  o.from = "paint";
  EXPECT_TRUE(Contains(ErrorOf([&] { o.Validate(); }), "from")) << ErrorOf([&] { o.Validate(); });
  o = {};
  o.until = "nowhere";
  EXPECT_TRUE(Contains(ErrorOf([&] { o.Validate(); }), "until"));
  o = {};
  o.from = "simulate";
  o.until = "register";
  EXPECT_TRUE(Contains(ErrorOf([&] { o.Validate(); }), "until"));
  o = {};
  o.held_out_markers = -1;
  EXPECT_TRUE(Contains(ErrorOf([&] { o.Validate(); }), "held_out_markers"));
  o = {};
  o.render_width = 3;
  EXPECT_TRUE(Contains(ErrorOf([&] { o.Validate(); }), "render_width"));
  o = {};
  o.from = "identify";
  o.until = "identify";
  EXPECT_NO_THROW(o.Validate());
}

TEST(StageTable, StagesInPipelineOrderEachWithItsFolder) {
  const std::vector<std::string> expected = {"preprocess", "register", "reconstruct",
                                             "track",      "identify", "build",
                                             "simulate",   "render",   "report"};
  EXPECT_EQ(StageNames(), expected);
  for (const Stage& s : StageTable()) {
    ASSERT_FALSE(s.outputs.empty()) << s.name;
    if (s.folder) {
      EXPECT_EQ(s.outputs.front(), s.name);
    }
    for (const std::string& input : s.inputs) {
      EXPECT_FALSE(Contains(input, "gt/")) << s.name << " reads " << input;
    }
  }
}

// A capture-shaped folder: scans/view_00/, pull/frames.csv, pull/markers.json.
fs::path FakeCapture(const fs::path& dir) {
  fs::create_directories(dir / "scans" / "view_00");
  fs::create_directories(dir / "pull");
  simtree::test::WriteText(dir / "pull" / "frames.csv", "frame,time_s,color,depth\n");
  simtree::test::WriteText(dir / "pull" / "markers.json", "{}");
  simtree::test::WriteText(dir / "tracks.csv", "");
  return dir;
}

TEST(CheckInputs, BadCapturesFailBeforeAnyWorkNamingWhatIsMissing) {
  const fs::path root = simtree::test::TempDir();
  RunOptions o;
  o.tracks = FakeCapture(root / "ok") / "tracks.csv";
  EXPECT_EQ(ErrorOf([&] { CheckInputs(root / "ok", root / "result", o); }), "");

  FakeCapture(root / "no_scans");
  fs::remove_all(root / "no_scans" / "scans" / "view_00");
  EXPECT_TRUE(Contains(ErrorOf([&] { CheckInputs(root / "no_scans", root / "r", o); }), "scans/"));

  FakeCapture(root / "no_pull");
  fs::remove_all(root / "no_pull" / "pull");
  EXPECT_TRUE(Contains(ErrorOf([&] { CheckInputs(root / "no_pull", root / "r", o); }), "pull/"));

  FakeCapture(root / "no_markers");
  fs::remove(root / "no_markers" / "pull" / "markers.json");
  EXPECT_TRUE(
      Contains(ErrorOf([&] { CheckInputs(root / "no_markers", root / "r", o); }), "markers.json"));
  EXPECT_TRUE(
      Contains(ErrorOf([&] { CheckInputs(root / "no_markers", root / "r", o); }), "capture-from"));

  EXPECT_TRUE(Contains(ErrorOf([&] { CheckInputs(root / "ok", root / "ok", o); }), "capture"));
  EXPECT_TRUE(
      Contains(ErrorOf([&] { CheckInputs(root / "ok", root / "ok" / "result", o); }), "capture"));
  EXPECT_TRUE(
      Contains(ErrorOf([&] { CheckInputs(root / "missing", root / "r", o); }), "capture folder"));

  RunOptions track;
  EXPECT_TRUE(Contains(ErrorOf([&] { CheckInputs(root / "ok", root / "r", track); }), "init.json"));
  simtree::test::WriteText(root / "ok" / "pull" / "init.json", "{}");
  EXPECT_EQ(ErrorOf([&] { CheckInputs(root / "ok", root / "r", track); }), "");

  o.tracks = root / "nope.csv";
  EXPECT_TRUE(Contains(ErrorOf([&] { CheckInputs(root / "ok", root / "r", o); }), "nope.csv"));
}

TEST(RunPipeline, RefusesBadInputsWithoutWritingAnything) {
  const fs::path root = simtree::test::TempDir();
  FakeCapture(root / "capture");
  fs::remove(root / "capture" / "pull" / "markers.json");
  RunOptions o;
  o.tracks = root / "capture" / "tracks.csv";
  EXPECT_THROW(simtree::pipeline::Run(root / "capture", root / "result", o), simtree::InputError);
  EXPECT_FALSE(fs::exists(root / "result"));
}

}  // namespace
