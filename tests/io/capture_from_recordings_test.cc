// CaptureFromRecordings on the real recording (as both a scan and the pull stream), and the
// still-frame choice on made-up scores.

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "simtree/io/capture.h"
#include "simtree/io/capture_from_recordings.h"
#include "simtree/io/detail/still_frame.h"
#include "test_util.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;

TEST(CaptureFromRecordings, TheRealRecordingBecomesAViewAndAPullStream) {
  const auto recording = test::SharedData("azure-kinect/pyk4a_recording.mkv");
  CaptureFromOptions options;
  options.scans = {recording};
  options.pull = recording;
  options.write_check_images = true;
  const auto root = test::TempDir() / "capture";
  const CaptureFromResult result = CaptureFromRecordings(options, root);
  ASSERT_EQ(result.views.size(), 1u);
  EXPECT_EQ(result.views[0].view, "view_00");
  EXPECT_EQ(result.views[0].candidates, 1);
  EXPECT_EQ(result.pull_frames, 1);
  EXPECT_EQ(result.sensor, "azure_kinect_nfov_unbinned");

  const Capture capture = OpenCapture(root);
  ASSERT_EQ(capture.views.size(), 1u);
  ASSERT_TRUE(capture.pull.has_value());
  EXPECT_EQ(capture.pull->frames.size(), 1u);
  const RgbdImage view = LoadScanView(capture.views[0]);
  EXPECT_EQ(view.intrinsics.width, 1280);
  EXPECT_EQ(view.intrinsics.height, 720);
  EXPECT_NEAR(view.intrinsics.fx, 0.4779651165008545 * 1280, 1e-6);
  // Depth registered into colour: a desk scene 0.3-4 m away, over half the colour image (the
  // rest is outside the depth camera's view or in its shadow).
  std::vector<uint16_t> valid;
  for (uint16_t mm : view.depth.pixels) {
    if (mm > 0) valid.push_back(mm);
  }
  EXPECT_GT(static_cast<double>(valid.size()) / view.depth.pixels.size(), 0.45);
  std::nth_element(valid.begin(), valid.begin() + valid.size() / 2, valid.end());
  EXPECT_GT(valid[valid.size() / 2], 300);
  EXPECT_LT(valid[valid.size() / 2], 4000);
  // The check pictures: two half-size panels.
  const RgbImage check = ReadColorImage(root / "check" / "view_00.png");
  EXPECT_EQ(check.width, 1280);
  EXPECT_EQ(check.height, 360);
  EXPECT_TRUE(fs::exists(root / "check" / "pull_first.png"));
  const RgbdImage frame = LoadPullFrame(*capture.pull, 0);
  EXPECT_EQ(frame.depth, view.depth);
  EXPECT_EQ(capture.pull->intrinsics, view.intrinsics);
}

// A textured scene 1.5 m away: shifted by `shift` pixels, box-blurred over `blur` pixels.
AzureCapture Scene(int64_t t_us, int shift, int blur) {
  AzureCapture c;
  c.color_timestamp_us = c.depth_timestamp_us = t_us;
  c.color.emplace(1280, 720);
  for (int y = 0; y < 720; ++y) {
    for (int x = 0; x < 1280; ++x) {
      int sum = 0;
      for (int k = 0; k < blur; ++k) sum += (((x + shift + k) / 8 + y / 8) % 2) ? 200 : 40;
      for (int ch = 0; ch < 3; ++ch) c.color->at(x, y, ch) = static_cast<uint8_t>(sum / blur);
    }
  }
  c.depth.emplace(320, 288, 1500);
  return c;
}

TEST(CaptureFromRecordings, PicksTheSharpStillCaptureAndKeepsPullTimes) {
  const auto dir = test::TempDir();
  AzureWriterOptions o;
  o.color_format = AzureColorFormat::kBgra;
  o.color_width = 1280;
  o.color_height = 720;
  o.depth_width = 320;
  o.depth_height = 288;
  o.calibration_json = test::ReadText(test::SharedData("azure-kinect/pyk4a_calibration.json"));
  {
    // Moving, still but blurred (1, 2), still and sharp (3, 4; 5 moves to 6), moving.
    AzureKinectWriter writer(dir / "scan.mkv", o);
    const int shifts[] = {0, 20, 20, 20, 20, 20, 40};
    const int blurs[] = {1, 5, 5, 1, 1, 1, 1};
    for (int i = 0; i < 7; ++i) writer.Write(Scene(100000 + i * 200000, shifts[i], blurs[i]));
    writer.Close();
  }
  {
    // 5 fps; capture 2 dropped.
    AzureKinectWriter writer(dir / "pull.mkv", o);
    for (int i : {0, 1, 3, 4}) writer.Write(Scene(50000 + i * 200000, i, 1));
    writer.Close();
  }
  CaptureFromOptions options;
  options.scans = {dir / "scan.mkv"};
  options.pull = dir / "pull.mkv";
  const CaptureFromResult result = CaptureFromRecordings(options, dir / "capture");
  ASSERT_EQ(result.views.size(), 1u);
  EXPECT_EQ(result.views[0].candidates, 7);
  EXPECT_EQ(result.views[0].capture, 3);  // the first of the sharp still ones
  EXPECT_EQ(result.views[0].timestamp_us, 700000);
  const Capture capture = OpenCapture(dir / "capture");
  ASSERT_EQ(capture.pull->frames.size(), 4u);
  const std::vector<int> numbers = {0, 1, 3, 4};
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(capture.pull->frames[i].frame, numbers[i]);
    EXPECT_NEAR(capture.pull->frames[i].time_s, 0.2 * numbers[i], 1e-9);
  }
  EXPECT_EQ(LoadPullFrame(*capture.pull, 3).depth.width, 1280);
}

TEST(StillFrame, PicksTheSharpestOfTheFramesThatMoveLeast) {
  // Frame 1 is sharpest but moving; of the still frames 0, 2, 3, frame 3 is sharpest.
  const std::vector<double> sharpness = {10, 50, 20, 30, 5};
  const std::vector<double> motion = {0.5, 9.0, 0.2, 0.8, 0.1};
  int still = 0;
  EXPECT_EQ(azure_detail::PickStill(sharpness, motion, 1.0, &still), 3);
  EXPECT_EQ(still, 4);
  // With no threshold the least-moving quarter (motion <= 0.2: frames 2 and 4) qualifies.
  EXPECT_EQ(azure_detail::PickStill(sharpness, motion, 0.0, &still), 2);
  EXPECT_EQ(still, 2);
}

TEST(StillFrame, BlurLowersSharpnessAndChangeRaisesMotion) {
  RgbImage sharp(64, 64);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) sharp.at(x, y, 1) = ((x / 4 + y / 4) % 2) ? 200 : 50;
  }
  RgbImage blurred = sharp;
  for (int y = 1; y < 63; ++y) {
    for (int x = 1; x < 63; ++x) {
      blurred.at(x, y, 1) = static_cast<uint8_t>((sharp.at(x - 1, y, 1) + sharp.at(x + 1, y, 1) +
                                                  sharp.at(x, y - 1, 1) + sharp.at(x, y + 1, 1)) /
                                                 4);
    }
  }
  EXPECT_GT(azure_detail::Sharpness(sharp), 2 * azure_detail::Sharpness(blurred));
  EXPECT_EQ(azure_detail::Motion(azure_detail::Shrink(sharp), azure_detail::Shrink(sharp)), 0.0);
  EXPECT_GT(azure_detail::Motion(azure_detail::Shrink(sharp), azure_detail::Shrink(blurred)), 0.0);
}

}  // namespace
}  // namespace simtree
