// RealSense .bag files (ROS bag 2.0) written by the test's own writer (below, after the ROS wiki's
// record layout): records in a chunk (uncompressed, lz4, bz2), colour and depth sensor_msgs/Image
// topics with their sensor_msgs/CameraInfo and the Depth Units option; pairing by header stamp,
// depth units, pixel placement, and the bags simtree refuses.

#include <cstring>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#ifdef SIMTREE_HAVE_LZ4
#include <lz4frame.h>
#endif
#ifdef SIMTREE_HAVE_BZ2
#include <bzlib.h>
#endif

#include "simtree/io/capture_from_recordings.h"
#include "simtree/io/detail/ros_bag.h"
#include "simtree/io/realsense_bag.h"
#include "simtree/io/recording_layout.h"
#include "test_util.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr int kWidth = 16;
constexpr int kHeight = 12;

// ROS 1 serialization.
struct Ser {
  std::string bytes;
  template <typename T>
  Ser& Put(T v) {
    bytes.append(reinterpret_cast<const char*>(&v), sizeof(T));
    return *this;
  }
  Ser& Str(const std::string& s) {
    Put<uint32_t>(static_cast<uint32_t>(s.size()));
    bytes += s;
    return *this;
  }
  Ser& Stamp(double t) {
    Put<uint32_t>(0);
    Put<uint32_t>(static_cast<uint32_t>(t));
    Put<uint32_t>(static_cast<uint32_t>(std::llround((t - static_cast<uint32_t>(t)) * 1e9)));
    return Str("frame");
  }
};

std::string Field(const std::string& name, const std::string& value) {
  Ser s;
  s.Str(name + "=" + value);
  return s.bytes;
}
template <typename T>
std::string Bin(T v) {
  return std::string(reinterpret_cast<const char*>(&v), sizeof(T));
}
std::string Record(const std::string& header, const std::string& data) {
  Ser s;
  s.Str(header).Str(data);
  return s.bytes;
}
std::string Connection(uint32_t id, const std::string& topic, const std::string& type) {
  return Record(Field("op", "\x07") + Field("conn", Bin(id)) + Field("topic", topic),
                Field("topic", topic) + Field("type", type) + Field("md5sum", "0"));
}
std::string Message(uint32_t id, double t, const std::string& data) {
  const std::string time = Bin(static_cast<uint32_t>(t)) + Bin(uint32_t{0});
  return Record(Field("op", "\x02") + Field("conn", Bin(id)) + Field("time", time), data);
}

// Colour (x * 10, y * 20, frame * 30) as bgr8; depth raw 1000 + 7x + y (Depth Units 0.0001 m:
// 100 + 0.7x + 0.1y mm).
std::string ColorImage(double t, int frame) {
  Ser s;
  s.Stamp(t).Put<uint32_t>(kHeight).Put<uint32_t>(kWidth).Str("bgr8").Put<uint8_t>(0).Put<uint32_t>(
      kWidth * 3);
  std::string px;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      px += static_cast<char>(frame * 30);
      px += static_cast<char>(y * 20);
      px += static_cast<char>(x * 10);
    }
  }
  s.Str(px);
  return s.bytes;
}
std::string DepthImage16(double t, int width = kWidth) {
  Ser s;
  s.Stamp(t)
      .Put<uint32_t>(kHeight)
      .Put<uint32_t>(width)
      .Str("mono16")
      .Put<uint8_t>(0)
      .Put<uint32_t>(width * 2);
  std::string px;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < width; ++x) px += Bin(static_cast<uint16_t>(1000 + 7 * x + y));
  }
  s.Str(px);
  return s.bytes;
}
std::string CameraInfo(double fx) {
  Ser s;
  s.Stamp(0).Put<uint32_t>(kHeight).Put<uint32_t>(kWidth).Str("plumb_bob").Put<uint32_t>(5);
  for (int i = 0; i < 5; ++i) s.Put<double>(0);
  const double k[9] = {fx, 0, 7.5, 0, fx + 1, 5.5, 0, 0, 1};
  for (double v : k) s.Put<double>(v);
  for (int i = 0; i < 9 + 12; ++i) s.Put<double>(0);  // R, P
  s.Put<uint32_t>(0).Put<uint32_t>(0);                // binning
  for (int i = 0; i < 4; ++i) s.Put<uint32_t>(0);     // roi
  s.Put<uint8_t>(0);
  return s.bytes;
}

struct BagSpec {
  std::string compression = "none";
  double depth_fx = 14;  // the colour camera's fx is 14: equal means registered
  int depth_width = kWidth;
};

// The chunk's data as `compression` stores it ("broken": bytes no decompressor accepts).
std::string Compress(const std::string& data, const std::string& compression) {
#ifdef SIMTREE_HAVE_LZ4
  if (compression == "lz4") {
    std::string out(LZ4F_compressFrameBound(data.size(), nullptr), '\0');
    out.resize(LZ4F_compressFrame(out.data(), out.size(), data.data(), data.size(), nullptr));
    return out;
  }
#endif
#ifdef SIMTREE_HAVE_BZ2
  if (compression == "bz2") {
    std::string in = data;
    unsigned int length = static_cast<unsigned int>(data.size() + data.size() / 100 + 600);
    std::string out(length, '\0');
    BZ2_bzBuffToBuffCompress(out.data(), &length, in.data(), static_cast<unsigned int>(in.size()),
                             9, 0, 0);
    out.resize(length);
    return out;
  }
#endif
  if (compression == "broken") return std::string(data.size() / 2, 'x');
  return data;
}

std::string BagBytes(const BagSpec& spec) {
  std::string chunk;
  chunk += Connection(0, "/device_0/sensor_1/Color_0/image/data", "sensor_msgs/Image");
  chunk += Connection(1, "/device_0/sensor_0/Depth_0/image/data", "sensor_msgs/Image");
  chunk += Connection(2, "/device_0/sensor_1/Color_0/info/camera_info", "sensor_msgs/CameraInfo");
  chunk += Connection(3, "/device_0/sensor_0/Depth_0/info/camera_info", "sensor_msgs/CameraInfo");
  chunk += Connection(4, "/device_0/sensor_0/option/Depth Units/value", "std_msgs/Float32");
  chunk += Message(2, 1, CameraInfo(14));
  chunk += Message(3, 1, CameraInfo(spec.depth_fx));
  chunk += Message(4, 1, Bin(0.0001f));
  // Depth written before colour, out of order, as bags may interleave them.
  chunk += Message(1, 1, DepthImage16(1.035, spec.depth_width));
  chunk += Message(1, 1, DepthImage16(1.002, spec.depth_width));
  chunk += Message(1, 1, DepthImage16(1.300, spec.depth_width));
  for (int i = 0; i < 3; ++i) chunk += Message(0, 1, ColorImage(1.0 + 0.033 * i, i));
  std::string bag = "#ROSBAG V2.0\n";
  bag += Record(Field("op", "\x03") + Field("index_pos", Bin(uint64_t{0})) +
                    Field("conn_count", Bin(uint32_t{5})) + Field("chunk_count", Bin(uint32_t{1})),
                std::string(64, ' '));
  const std::string compression = spec.compression == "broken" ? "bz2" : spec.compression;
  bag += Record(Field("op", "\x05") + Field("compression", compression) +
                    Field("size", Bin(static_cast<uint32_t>(chunk.size()))),
                Compress(chunk, spec.compression));
  // The index section repeats the connections after the chunks.
  bag += Connection(0, "/device_0/sensor_1/Color_0/image/data", "sensor_msgs/Image");
  return bag;
}

fs::path WriteBag(const fs::path& path, const BagSpec& spec = {}) {
  test::WriteText(path, BagBytes(spec));
  return path;
}

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

}  // namespace
}  // namespace simtree
