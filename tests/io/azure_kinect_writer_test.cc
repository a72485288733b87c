// Recordings of the Azure layout written by AzureKinectWriter and read back by AzureKinectReader:
// the colour formats and depth modes the real file lacks, timestamps, dropped frames, bad input.

#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/io/azure_kinect.h"
#include "simtree/io/detail/track_clock.h"
#include "test_util.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;

std::string Calibration() {
  return test::ReadText(test::SharedData("azure-kinect/pyk4a_calibration.json"));
}

// Colour constant over 2x2 blocks (so NV12 and YUY2 chroma subsampling loses nothing) and
// different per frame; depth a pattern over the whole millimetre range.
AzureCapture MakeCapture(int frame, int64_t t_us, int cw, int ch, int dw, int dh) {
  AzureCapture c;
  c.color_timestamp_us = c.depth_timestamp_us = t_us;
  c.color.emplace(cw, ch);
  for (int y = 0; y < ch; ++y) {
    for (int x = 0; x < cw; ++x) {
      const int b = (x / 2) * 31 + (y / 2) * 17 + frame * 50;
      c.color->at(x, y, 0) = static_cast<uint8_t>(40 + b % 170);
      c.color->at(x, y, 1) = static_cast<uint8_t>(40 + (b / 3) % 170);
      c.color->at(x, y, 2) = static_cast<uint8_t>(40 + (b / 7) % 170);
    }
  }
  c.depth.emplace(dw, dh);
  for (int y = 0; y < dh; ++y) {
    for (int x = 0; x < dw; ++x)
      c.depth->at(x, y) = static_cast<uint16_t>((x * 7 + y * 131 + frame * 1000) % 65536);
  }
  c.ir = c.depth;
  return c;
}

struct Layout {
  AzureColorFormat format;
  int cw, ch, dw, dh;
  // Colour levels: the largest error for the raw formats (0 for BGRA; 8-bit YUV rounding for
  // NV12/YUY2), the mean error for MJPEG (lossy).
  int tolerance;
};

fs::path WriteRecording(const fs::path& path, const Layout& l, const std::vector<int64_t>& times) {
  AzureWriterOptions o;
  o.color_format = l.format;
  o.color_width = l.cw;
  o.color_height = l.ch;
  o.depth_width = l.dw;
  o.depth_height = l.dh;
  o.ir = true;
  o.calibration_json = Calibration();
  AzureKinectWriter writer(path, o);
  for (size_t i = 0; i < times.size(); ++i) {
    writer.Write(MakeCapture(static_cast<int>(i), times[i], l.cw, l.ch, l.dw, l.dh));
  }
  writer.Close();
  return path;
}

TEST(AzureKinectWriter, EveryColourFormatAndDepthModeReadsBackFrameExact) {
  const std::vector<Layout> layouts = {{AzureColorFormat::kBgra, 1280, 720, 640, 576, 0},
                                       {AzureColorFormat::kNv12, 1280, 720, 512, 512, 5},
                                       {AzureColorFormat::kYuy2, 1280, 720, 1024, 1024, 5},
                                       {AzureColorFormat::kMjpeg, 2048, 1536, 320, 288, 3}};
  const std::vector<int64_t> times = {200000, 233000, 267000};
  for (const Layout& l : layouts) {
    const fs::path path = WriteRecording(test::TempDir() / "rec.mkv", l, times);
    AzureReaderOptions options;
    options.read_ir = true;
    AzureKinectReader reader(path, options);
    SCOPED_TRACE(reader.FindTrack("COLOR")->fourcc);
    EXPECT_EQ(reader.FindTrack("DEPTH")->fourcc, "b16g");
    EXPECT_EQ(reader.calibration().depth.width, l.dw);
    EXPECT_EQ(reader.calibration().color.height, l.ch);
    for (size_t i = 0; i < times.size(); ++i) {
      const std::optional<AzureCapture> got = reader.Next();
      ASSERT_TRUE(got.has_value());
      const AzureCapture want = MakeCapture(static_cast<int>(i), times[i], l.cw, l.ch, l.dw, l.dh);
      EXPECT_EQ(got->color_timestamp_us, times[i]);
      EXPECT_EQ(got->depth_timestamp_us, times[i]);
      ASSERT_TRUE(got->depth && got->ir && got->color);
      EXPECT_TRUE(*got->depth == *want.depth);
      EXPECT_TRUE(*got->ir == *want.ir);
      int worst = 0;
      double sum = 0;
      for (size_t p = 0; p < want.color->pixels.size(); ++p) {
        const int error = std::abs(got->color->pixels[p] - want.color->pixels[p]);
        worst = std::max(worst, error);
        sum += error;
      }
      if (l.format == AzureColorFormat::kMjpeg) {
        EXPECT_LE(sum / want.color->pixels.size(), l.tolerance);
      } else {
        EXPECT_LE(worst, l.tolerance);
      }
    }
    EXPECT_FALSE(reader.Next().has_value());
    EXPECT_EQ(reader.stats().captures, 3);
  }
}

TEST(AzureKinectWriter, DroppedAndUnpairedFramesAreCounted) {
  const fs::path path = test::TempDir() / "drops.mkv";
  AzureWriterOptions o;
  o.color_format = AzureColorFormat::kBgra;
  o.color_width = 64;
  o.color_height = 36;
  o.depth_width = 640;
  o.depth_height = 576;
  o.calibration_json = Calibration();
  {
    AzureKinectWriter writer(path, o);
    // 30 fps for 12 captures; capture 4 missing, capture 8 without its depth frame.
    for (int i = 0; i < 12; ++i) {
      if (i == 4) continue;
      AzureCapture c = MakeCapture(0, (i * 100000 + 1) / 3 / 1000 * 1000, 64, 36, 640, 576);
      c.ir.reset();
      if (i == 8) c.depth.reset();
      writer.Write(c);
    }
    writer.Close();
  }
  AzureKinectReader reader(path);
  int captures = 0;
  while (reader.Next()) ++captures;
  const AzureReadStats& s = reader.stats();
  EXPECT_EQ(captures, 11);
  EXPECT_EQ(s.color_frames, 11);
  EXPECT_EQ(s.depth_frames, 10);
  EXPECT_EQ(s.color_without_depth, 1);
  EXPECT_EQ(s.dropped_color, 1);
  EXPECT_EQ(s.dropped_depth, 2);  // captures 4 and 8
  EXPECT_NEAR(s.frame_rate_hz, 30.0, 1.0);
}

TEST(AzureKinectWriter, ADepthTrackOfNoModesSizeIsAnError) {
  const fs::path path = WriteRecording(test::TempDir() / "odd.mkv",
                                       {AzureColorFormat::kBgra, 64, 36, 640, 480, 0}, {0});
  const std::string error = test::ErrorOf<InputError>([&] { AzureKinectReader reader(path); });
  EXPECT_NE(error.find(path.string()), std::string::npos) << error;
  EXPECT_NE(error.find("expected a depth mode's size"), std::string::npos) << error;
}

TEST(AzureKinectWriter, WithoutCloseNoFileAppears) {
  const fs::path path = test::TempDir() / "unfinished.mkv";
  {
    AzureWriterOptions o;
    o.depth_width = 320;
    o.depth_height = 288;
    AzureKinectWriter writer(path, o);
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(path.parent_path()));
}

TEST(TrackClock, TimestampsThatGoBackAreAnErrorNamingTheFrame) {
  azure_detail::TrackClock clock("rec.mkv", "DEPTH");
  clock.Add(1000);
  clock.Add(34000);
  const std::string error = test::ErrorOf<InputError>([&] { clock.Add(20000); });
  EXPECT_NE(error.find("rec.mkv: DEPTH frame 2"), std::string::npos) << error;
  EXPECT_NE(error.find("go back"), std::string::npos) << error;
}

}  // namespace
}  // namespace simtree
