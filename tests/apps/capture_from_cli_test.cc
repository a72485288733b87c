// `simtree capture-from` on the real Azure Kinect recording, on a truncated copy, and on a TUM
// RGB-D folder written by the test (the camera options).

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "simtree/io/capture.h"
#include "simtree/io/image_io.h"
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

// Two 32x24 frames, depth 1.2 m in TUM's units (5000 per metre).
fs::path WriteTumFolder(const fs::path& dir) {
  fs::create_directories(dir / "rgb");
  fs::create_directories(dir / "depth");
  std::string rgb, depth;
  for (const std::string t : {"5.000000", "5.033333"}) {
    WritePng(RgbImage(32, 24, 90), dir / "rgb" / (t + ".png"));
    WritePng(DepthImage(32, 24, 6000), dir / "depth" / (t + ".png"));
    rgb += t + " rgb/" + t + ".png\n";
    depth += t + " depth/" + t + ".png\n";
  }
  test::WriteText(dir / "rgb.txt", rgb);
  test::WriteText(dir / "depth.txt", depth);
  return dir;
}

TEST(CaptureFromCli, ATumFolderNeedsItsCameraNamed) {
  const fs::path dir = test::TempDir();
  const fs::path tum = WriteTumFolder(dir / "tum");
  const fs::path out = dir / "capture";
  const std::string base =
      "-q capture-from --pull \"" + tum.string() + "\" --out \"" + out.string() + "\"";
  test::CliResult r = test::RunCli(base);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("intrinsics: expected the camera"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));

  WriteIntrinsicsJson({32, 24, 30, 30, 15.5, 11.5, 0.001}, dir / "k.json");
  r = test::RunCli(base + " --intrinsics \"" + (dir / "k.json").string() + "\" --camera tum-fr3");
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("not both"), std::string::npos) << r.output;

  r = test::RunCli(base + " --intrinsics \"" + (dir / "k.json").string() + "\"");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Capture capture = OpenCapture(out);
  EXPECT_EQ(capture.info.sensor, "tum_rgbd");
  ASSERT_TRUE(capture.pull.has_value());
  EXPECT_EQ(capture.pull->frames.size(), 2u);
  EXPECT_EQ(LoadPullFrame(*capture.pull, 1).depth.at(3, 3), 1200);
}

}  // namespace
}  // namespace simtree
