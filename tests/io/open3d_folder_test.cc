// Open3D reconstruction-system folders written by the test-support writer
// (tests/support/open3d_folder_writer.h): the intrinsic JSON, depth scale,
// pairing in name order, bad folders, and the folder through CaptureFromRecordings.

#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "simtree/io/capture_from_recordings.h"
#include "simtree/io/intrinsics_file.h"
#include "simtree/io/open3d_folder.h"
#include "simtree/io/recording_layout.h"
#include "support/open3d_folder_writer.h"
#include "test_util.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;

using test::WriteOpen3dFolder;

TEST(Open3dFolder, ReadsTheCameraAndDepthInItsScale) {
  const fs::path tmp = test::TempDir();
  const fs::path dir = WriteOpen3dFolder(tmp / "dataset", 3, "intrinsic.json");
  EXPECT_EQ(DetectLayout(dir), RecordingLayout::kOpen3dFolder);
  const auto seq = OpenOpen3dFolder(dir, {});
  ASSERT_EQ(seq->size(), 3u);
  EXPECT_EQ(seq->sensor(), "open3d_folder");
  const CameraIntrinsics& k = seq->intrinsics();
  EXPECT_EQ(k.width, 40);
  EXPECT_EQ(k.fx, 35.0);
  EXPECT_EQ(k.fy, 36.0);
  EXPECT_EQ(k.cx, 19.5);
  EXPECT_EQ(k.cy, 14.5);
  EXPECT_NEAR(seq->time_s(2), 2.0 / 30, 1e-12);
  const RgbdImage frame = seq->Load(1);
  EXPECT_EQ(frame.depth.at(4, 3), 2000 + 12 + 3 + 100);  // scale 1000: millimetres as stored
  EXPECT_EQ(frame.color.at(4, 3, 0), 24);
  EXPECT_EQ(frame.color.at(4, 3, 2), 50);

  // Another depth scale: 4000 units per metre are a quarter millimetre each.
  Open3dFolderOptions options;
  options.depth_scale = 4000;
  EXPECT_EQ(OpenOpen3dFolder(dir, options)->Load(0).depth.at(0, 0), 500);
}

TEST(Open3dFolder, AcceptsTheRecordersFileNameAndRefusesARowMajorMatrix) {
  const fs::path tmp = test::TempDir();
  const fs::path dir = WriteOpen3dFolder(tmp / "dataset", 1, "camera_intrinsic.json");
  EXPECT_EQ(DetectLayout(dir), RecordingLayout::kOpen3dFolder);
  test::WriteText(dir / "camera_intrinsic.json",
                  R"({"width": 40, "height": 30,
                      "intrinsic_matrix": [35.0, 0.0, 19.5, 0.0, 36.0, 14.5, 0.0, 0.0, 1.0]})");
  const std::string message = test::ErrorOf([&] { OpenOpen3dFolder(dir, {}); });
  EXPECT_NE(message.find("intrinsic_matrix: expected [fx, 0, 0, 0, fy, 0, cx, cy, 1]"),
            std::string::npos)
      << message;
  // The same file read as a user's camera for a TUM sequence, both formats.
  test::WriteText(dir / "k.json",
                  R"({"width": 40, "height": 30,
                      "intrinsic_matrix": [35.0, 0.0, 0.0, 0.0, 36.0, 0.0, 19.5, 14.5, 1.0]})");
  EXPECT_EQ(ReadIntrinsicsFile(dir / "k.json").cy, 14.5);
  WriteIntrinsicsJson({40, 30, 35, 36, 19.5, 14.5, 0.001}, dir / "simtree.json");
  EXPECT_EQ(ReadIntrinsicsFile(dir / "simtree.json").fy, 36.0);
}

TEST(Open3dFolder, CountsThatDifferAreRefused) {
  const fs::path tmp = test::TempDir();
  const fs::path dir = WriteOpen3dFolder(tmp / "dataset", 3, "intrinsic.json");
  fs::remove(dir / "depth" / "000002.png");
  const std::string message = test::ErrorOf([&] { OpenOpen3dFolder(dir, {}); });
  EXPECT_NE(message.find("got 3 in color and 2 in depth/"), std::string::npos) << message;
}

TEST(Open3dFolder, BecomesTheCapturesPullStream) {
  const fs::path tmp = test::TempDir();
  const fs::path dir = WriteOpen3dFolder(tmp / "dataset", 4, "intrinsic.json");
  CaptureFromOptions options;
  options.pull = dir;
  options.sequence.fps = 15;
  const fs::path root = tmp / "capture";
  const CaptureFromResult result = CaptureFromRecordings(options, root);
  EXPECT_EQ(result.pull_frames, 4);
  EXPECT_NEAR(result.pull_stats.frame_rate_hz, 15, 1e-9);
  const Capture capture = OpenCapture(root);
  ASSERT_TRUE(capture.pull.has_value());
  EXPECT_EQ(capture.pull->frames.back().frame, 3);
  EXPECT_NEAR(capture.pull->frames.back().time_s, 0.2, 1e-9);
  EXPECT_EQ(LoadPullFrame(*capture.pull, 3).depth.at(0, 0), 2300);
}

}  // namespace
}  // namespace simtree
