// TUM RGB-D sequences written by the test-support writer (tests/support/tum_rgbd_writer.h): lists,
// pairing by time, depth units, pixel placement, bad lists, and a sequence through
// CaptureFromRecordings as a scan view and as the pull stream.

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "simtree/core/atomic_file.h"
#include "simtree/io/capture_from_recordings.h"
#include "simtree/io/detail/time_association.h"
#include "simtree/io/recording_layout.h"
#include "simtree/io/tum_rgbd.h"
#include "support/tum_rgbd_writer.h"
#include "test_util.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;

using test::kTumHeight;
using test::kTumWidth;
using test::WriteTumSequence;

// TUM's fr3 camera scaled to the test's 32x24 images.
TumRgbdOptions Fr3() {
  TumRgbdOptions o;
  CameraIntrinsics k = TumCamera("tum-fr3");
  const double s = static_cast<double>(kTumWidth) / k.width;
  o.intrinsics =
      CameraIntrinsics{kTumWidth, kTumHeight, k.fx * s, k.fy * s, k.cx * s, k.cy * s, 0.001};
  return o;
}

TEST(TumRgbd, PairsByNearestTimeAndGivesMillimetres) {
  const fs::path tmp = test::TempDir();
  const fs::path dir = WriteTumSequence(tmp / "seq");
  EXPECT_EQ(DetectLayout(dir), RecordingLayout::kTumRgbd);
  const auto seq = OpenTumRgbd(dir, Fr3());
  ASSERT_EQ(seq->size(), 3u);
  EXPECT_EQ(seq->sensor(), "tum_rgbd");
  EXPECT_DOUBLE_EQ(seq->time_s(0), 10.0);
  EXPECT_DOUBLE_EQ(seq->time_s(2), 10.067);
  EXPECT_DOUBLE_EQ(seq->intrinsics().fx, 535.4 * 0.05);
  EXPECT_EQ(seq->intrinsics().depth_scale_m, 0.001);
  const RgbdImage frame = seq->Load(2);
  EXPECT_EQ(frame.color.at(5, 7, 0), 40);
  EXPECT_EQ(frame.color.at(5, 7, 1), 56);
  EXPECT_EQ(frame.color.at(5, 7, 2), 80);  // the third colour image
  EXPECT_EQ(frame.depth.at(0, 0), 1000);
  EXPECT_EQ(frame.depth.at(5, 7), 1075);
  EXPECT_EQ(frame.depth.at(kTumWidth - 1, kTumHeight - 1), 1000 + 31 + 230);
}

TEST(TumRgbd, AssociationTakesTheClosestPairFirstAndUsesEachFrameOnce) {
  using io_detail::AssociateByTime;
  // 0.008 is 8 ms from 0.0 but 2 ms from 0.010: it goes to 0.010, and 0.0 stays alone.
  const auto pairs = AssociateByTime({0.0, 0.010, 0.033}, {0.008, 0.030, 0.5}, 0.02);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0], std::make_pair(size_t{1}, size_t{0}));
  EXPECT_EQ(pairs[1], std::make_pair(size_t{2}, size_t{1}));
  EXPECT_TRUE(AssociateByTime({0.0}, {0.1}, 0.02).empty());
}

TEST(TumRgbd, RefusesToGuessTheCamera) {
  const fs::path tmp = test::TempDir();
  const fs::path dir = WriteTumSequence(tmp / "seq");
  const std::string message = test::ErrorOf([&] { OpenTumRgbd(dir, TumRgbdOptions{}); });
  EXPECT_NE(message.find("intrinsics"), std::string::npos) << message;
  EXPECT_NE(message.find("tum-fr1"), std::string::npos) << message;
  EXPECT_NE(test::ErrorOf([] { TumCamera("freiburg9"); }).find("tum-fr2"), std::string::npos);
}

TEST(TumRgbd, BadListsNameTheFileAndLine) {
  const fs::path tmp = test::TempDir();
  const fs::path dir = WriteTumSequence(tmp / "seq");
  // A time that goes back.
  test::WriteText(dir / "rgb.txt",
                  "# t f\n10.000000 rgb/10.000000.png\n10.067000 rgb/10.067000.png\n"
                  "10.033000 rgb/10.033000.png\n");
  std::string message = test::ErrorOf([&] { OpenTumRgbd(dir, Fr3()); });
  EXPECT_NE(message.find("rgb.txt: line 4"), std::string::npos) << message;
  EXPECT_NE(message.find("must increase"), std::string::npos) << message;
  // An entry whose file is missing.
  test::WriteText(dir / "rgb.txt", "10.000000 rgb/10.000000.png\n10.033000 rgb/missing.png\n");
  message = test::ErrorOf([&] { OpenTumRgbd(dir, Fr3()); });
  EXPECT_NE(message.find("line 2"), std::string::npos) << message;
  EXPECT_NE(message.find("missing.png, which does not exist"), std::string::npos) << message;
  // A line without a file name.
  test::WriteText(dir / "rgb.txt", "10.000000\n");
  message = test::ErrorOf([&] { OpenTumRgbd(dir, Fr3()); });
  EXPECT_NE(message.find("expected \"timestamp filename\""), std::string::npos) << message;
  // No pair within the tolerance.
  test::WriteText(dir / "rgb.txt", "10.100000 rgb/10.100000.png\n");
  test::WriteText(dir / "depth.txt", "10.300000 depth/10.300000.png\n");
  message = test::ErrorOf([&] { OpenTumRgbd(dir, Fr3()); });
  EXPECT_NE(message.find("found none"), std::string::npos) << message;
}

TEST(TumRgbd, DepthOfTheWrongSizeIsRefusedAndNothingIsWritten) {
  const fs::path tmp = test::TempDir();
  const fs::path dir = WriteTumSequence(tmp / "seq");
  WritePng(test::TumRawDepth(kTumWidth / 2, kTumHeight / 2), dir / "depth" / "10.040000.png");
  const auto seq = OpenTumRgbd(dir, Fr3());
  const std::string message = test::ErrorOf([&] { seq->Load(1); });
  EXPECT_NE(message.find("10.040000.png: expected a 32x24 depth image"), std::string::npos)
      << message;

  CaptureFromOptions options;
  options.pull = dir;
  options.sequence.intrinsics = Fr3().intrinsics;
  const fs::path out = tmp / "capture";
  EXPECT_FALSE(test::ErrorOf([&] {
                 AtomicDirectory folder(out);
                 CaptureFromRecordings(options, folder.path());
                 folder.Commit();
               }).empty());
  EXPECT_FALSE(fs::exists(out));
}

TEST(TumRgbd, BecomesAScanViewAndThePullStream) {
  const fs::path tmp = test::TempDir();
  const fs::path dir = WriteTumSequence(tmp / "seq");
  CaptureFromOptions options;
  options.scans = {dir};
  options.pull = dir;
  options.sequence.intrinsics = Fr3().intrinsics;
  const fs::path root = tmp / "capture";
  const CaptureFromResult result = CaptureFromRecordings(options, root);
  EXPECT_EQ(result.sensor, "tum_rgbd");
  EXPECT_EQ(result.pull_layout, RecordingLayout::kTumRgbd);
  ASSERT_EQ(result.views.size(), 1u);
  EXPECT_EQ(result.views[0].candidates, 3);
  EXPECT_EQ(result.pull_frames, 3);

  const Capture capture = OpenCapture(root);
  EXPECT_EQ(capture.info.sensor, "tum_rgbd");
  ASSERT_EQ(capture.views.size(), 1u);
  const RgbdImage view = LoadScanView(capture.views[0]);
  EXPECT_EQ(view.depth.at(5, 7), 1075);
  EXPECT_DOUBLE_EQ(view.intrinsics.fy, 539.2 * 0.05);
  ASSERT_TRUE(capture.pull.has_value());
  const std::vector<PullFrame>& frames = capture.pull->frames;
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[0].frame, 0);
  EXPECT_EQ(frames[1].frame, 1);
  EXPECT_EQ(frames[2].frame, 2);
  EXPECT_NEAR(frames[1].time_s, 0.033, 1e-9);
  EXPECT_NEAR(frames[2].time_s, 0.067, 1e-9);
  const RgbdImage last = LoadPullFrame(*capture.pull, 2);
  EXPECT_EQ(last.color.at(5, 7, 2), 80);
  EXPECT_EQ(last.depth.at(kTumWidth - 1, 0), 1031);
}

}  // namespace
}  // namespace simtree
