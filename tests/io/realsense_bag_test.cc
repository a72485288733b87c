// RealSense .bag files (ROS bag 2.0) written by the test-support writer
// (tests/support/ros_bag_writer.h): pairing by header stamp, depth units, pixel placement,
// compressed chunks, and the bags simtree refuses.

#include <cstring>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/io/capture_from_recordings.h"
#include "simtree/io/detail/ros_bag.h"
#include "simtree/io/realsense_bag.h"
#include "simtree/io/recording_layout.h"
#include "support/ros_bag_writer.h"
#include "test_util.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using test::BagBytes;
using test::BagSpec;
using test::WriteBag;
constexpr int kWidth = test::kBagWidth;

TEST(RealSenseBag, PairsColourAndDepthByStampInTheBagsUnits) {
  const fs::path bag = WriteBag(test::TempDir() / "rec.bag");
  EXPECT_EQ(DetectLayout(bag), RecordingLayout::kRealSenseBag);
  const auto seq = OpenRealSenseBag(bag, {});
  ASSERT_EQ(seq->size(), 2u);  // the third colour frame has no depth within 20 ms
  EXPECT_EQ(seq->sensor(), "realsense_bag");
  EXPECT_NEAR(seq->time_s(0), 1.0, 1e-6);
  EXPECT_NEAR(seq->time_s(1), 1.033, 1e-6);
  EXPECT_EQ(seq->intrinsics().fx, 14);
  EXPECT_EQ(seq->intrinsics().fy, 15);
  EXPECT_EQ(seq->intrinsics().cx, 7.5);
  const RgbdImage frame = seq->Load(1);
  EXPECT_EQ(frame.color.at(3, 2, 0), 30);  // bgr8 read as RGB
  EXPECT_EQ(frame.color.at(3, 2, 1), 40);
  EXPECT_EQ(frame.color.at(3, 2, 2), 30);
  EXPECT_EQ(frame.depth.at(0, 0), 100);   // 1000 units of 0.1 mm
  EXPECT_EQ(frame.depth.at(10, 6), 108);  // 1076 units: 107.6 mm, rounded

  RealSenseBagOptions millimetres;
  millimetres.depth_units_per_m = 1000;
  EXPECT_EQ(OpenRealSenseBag(bag, millimetres)->Load(0).depth.at(10, 5), 1075);
}

TEST(RealSenseBag, BecomesThePullStream) {
  const fs::path tmp = test::TempDir();
  CaptureFromOptions options;
  options.pull = WriteBag(tmp / "pull.bag");
  const CaptureFromResult result = CaptureFromRecordings(options, tmp / "capture");
  EXPECT_EQ(result.sensor, "realsense_bag");
  EXPECT_EQ(result.pull_frames, 2);
  const Capture capture = OpenCapture(tmp / "capture");
  ASSERT_TRUE(capture.pull.has_value());
  EXPECT_NEAR(capture.pull->frames[1].time_s, 0.033, 1e-6);
  EXPECT_EQ(LoadPullFrame(*capture.pull, 0).depth.at(1, 0), 101);
}

TEST(RealSenseBag, CompressedChunksReadLikePlainOnes) {
  const fs::path tmp = test::TempDir();
  const RgbdImage plain = OpenRealSenseBag(WriteBag(tmp / "plain.bag"), {})->Load(1);
  for (const std::string compression : {"lz4", "bz2"}) {
    SCOPED_TRACE(compression);
    if (!io_detail::RosCompressionSupported(compression)) {
      GTEST_SKIP() << "built without " << compression;
    }
    BagSpec spec;
    spec.compression = compression;
    const fs::path bag = WriteBag(tmp / (compression + ".bag"), spec);
    EXPECT_LT(fs::file_size(bag), fs::file_size(tmp / "plain.bag"));  // really compressed
    const auto seq = OpenRealSenseBag(bag, {});
    ASSERT_EQ(seq->size(), 2u);
    const RgbdImage frame = seq->Load(1);
    EXPECT_EQ(frame.color, plain.color);
    EXPECT_EQ(frame.depth, plain.depth);
  }
}

TEST(RealSenseBag, RefusedBagsSayWhy) {
  const fs::path tmp = test::TempDir();
  BagSpec zstd;
  zstd.compression = "zstd";
  EXPECT_THAT(test::ErrorOf([&] { OpenRealSenseBag(WriteBag(tmp / "zstd.bag", zstd), {}); }),
              HasSubstr("a chunk compressed with zstd is not read by this build"));
  if (io_detail::RosCompressionSupported("bz2")) {
    BagSpec broken;
    broken.compression = "broken";
    EXPECT_THAT(test::ErrorOf([&] { OpenRealSenseBag(WriteBag(tmp / "broken.bag", broken), {}); }),
                HasSubstr("the bz2 chunk at byte"));
  }
  BagSpec unaligned;
  unaligned.depth_fx = 11;
  EXPECT_THAT(test::ErrorOf([&] { OpenRealSenseBag(WriteBag(tmp / "raw.bag", unaligned), {}); }),
              HasSubstr("expected depth registered to the colour image"));
  BagSpec narrow;
  narrow.depth_width = kWidth - 2;
  const auto seq = OpenRealSenseBag(WriteBag(tmp / "narrow.bag", narrow), {});
  EXPECT_THAT(test::ErrorOf([&] { seq->Load(0); }), HasSubstr("expected 16x12 pixels"));
  std::string truncated = BagBytes({});
  truncated.resize(truncated.size() / 2);
  test::WriteText(tmp / "truncated.bag", truncated);
  EXPECT_THAT(test::ErrorOf([&] { OpenRealSenseBag(tmp / "truncated.bag", {}); }),
              HasSubstr("runs past the end"));
  test::WriteText(tmp / "v1.bag", "#ROSBAG V1.2\n");
  EXPECT_THAT(test::ErrorOf([&] { OpenRealSenseBag(tmp / "v1.bag", {}); }),
              HasSubstr("expected a ROS bag version 2.0"));
}

// The fuzzer's input (fuzz/regressions/realsense_bag/): an lz4 chunk whose size field claims 4 GB
// uncompressed, which the reader allocated before decompressing.
TEST(RealSenseBag, AChunkClaimingGigabytesIsRefusedNotAllocated) {
  const fs::path bag =
      fs::path(SIMTREE_SOURCE_DIR) / "fuzz/regressions/realsense_bag/chunk_claims_4gb.bag";
  const std::string message = test::ErrorOf([&] { OpenRealSenseBag(bag, {}); });
  if (!io_detail::RosCompressionSupported("lz4")) GTEST_SKIP() << "built without lz4";
  EXPECT_THAT(message, HasSubstr("chunk_claims_4gb.bag: the lz4 chunk at byte"));
  EXPECT_THAT(message, HasSubstr("the header claims 4294962188"));
}

}  // namespace
}  // namespace simtree
