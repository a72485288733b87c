// `simtree capture-from` on the real Azure Kinect recording, and on a truncated copy.

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "test_util.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;

TEST(CaptureFromCli, TheRealRecordingBecomesACaptureAndTheUserIsToldWhatToAdd) {
  const fs::path recording = test::SharedData("azure-kinect/pyk4a_recording.mkv");
  const fs::path out = test::TempDir() / "capture";
  const test::CliResult r =
      test::RunCli("-q capture-from \"" + recording.string() + "\" --pull \"" + recording.string() +
                   "\" --out \"" + out.string() + "\"");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "capture.json"));
  EXPECT_TRUE(fs::exists(out / "scans/view_00/depth.png"));
  EXPECT_TRUE(fs::exists(out / "pull/frames.csv"));
  EXPECT_FALSE(fs::exists(out / "pull/markers.json"));
  EXPECT_NE(r.output.find("pull/markers.json"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("pull/init.json"), std::string::npos) << r.output;

  const test::CliResult help = test::RunCli("capture-from --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.output.find("markers.json"), std::string::npos);
  EXPECT_NE(help.output.find("Examples"), std::string::npos);
}

TEST(CaptureFromCli, ATruncatedRecordingFailsNamingItAndWritesNothing) {
  const std::string data = test::ReadText(test::SharedData("azure-kinect/pyk4a_recording.mkv"));
  const fs::path dir = test::TempDir();
  const fs::path cut = dir / "cut.mkv";
  test::WriteText(cut, data.substr(0, data.size() / 3));
  const fs::path out = dir / "capture";
  const test::CliResult r =
      test::RunCli("-q capture-from \"" + cut.string() + "\" --out \"" + out.string() + "\"");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(cut.string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("truncated"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace simtree
