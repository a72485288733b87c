// AzureKinectReader on the real k4arecorder file (read in place from the shared data), and on
// copies damaged at test time.

#include <algorithm>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/io/azure_kinect.h"
#include "test_util.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;

fs::path Recording() { return test::SharedData("azure-kinect/pyk4a_recording.mkv"); }

TEST(AzureKinectReader, ListsTheRecordersTracks) {
  AzureKinectReader reader(Recording());
  std::vector<std::string> names;
  for (const AzureTrack& t : reader.tracks()) names.push_back(t.name);
  EXPECT_EQ(names, (std::vector<std::string>{"COLOR", "DEPTH", "IR", "IMU"}));
  const AzureTrack* color = reader.FindTrack("COLOR");
  ASSERT_NE(color, nullptr);
  EXPECT_EQ(color->codec, "mjpeg");
  EXPECT_EQ(color->mode, "MJPG_720P");
  EXPECT_EQ(color->width, 1280);
  EXPECT_EQ(color->height, 720);
  const AzureTrack* depth = reader.FindTrack("DEPTH");
  ASSERT_NE(depth, nullptr);
  EXPECT_EQ(depth->fourcc, "b16g");
  EXPECT_EQ(depth->mode, "NFOV_UNBINNED");
  EXPECT_EQ(depth->width, 640);
  EXPECT_EQ(depth->height, 576);
  EXPECT_EQ(reader.depth_delay_us(), 0);
  EXPECT_EQ(reader.start_offset_us(), 336277);  // K4A_START_OFFSET_NS 336277000
}

TEST(AzureKinectReader, ReadsTheOneCaptureWithDepthInMillimetresAtTheRightPixels) {
  AzureReaderOptions options;
  options.read_ir = true;
  AzureKinectReader reader(Recording(), options);
  std::optional<AzureCapture> capture = reader.Next();
  ASSERT_TRUE(capture.has_value());
  EXPECT_EQ(capture->index, 0);
  EXPECT_EQ(capture->color_timestamp_us, 463945);
  EXPECT_EQ(capture->depth_timestamp_us, 463945);
  ASSERT_TRUE(capture->color && capture->depth && capture->ir);
  EXPECT_EQ(capture->color->width, 1280);
  EXPECT_EQ(capture->color->height, 720);
  EXPECT_EQ(capture->depth->width, 640);
  EXPECT_EQ(capture->depth->height, 576);
  // Values ffmpeg gives for the same track (`-map 0:1 -pix_fmt gray16le`): the byte order and
  // the pixel grid are right.
  EXPECT_EQ(capture->depth->at(320, 288), 1939);
  EXPECT_EQ(capture->depth->at(100, 100), 763);
  EXPECT_EQ(capture->depth->at(500, 400), 1459);
  EXPECT_EQ(capture->depth->at(200, 450), 254);
  EXPECT_EQ(capture->depth->at(600, 50), 0);
  // ffmpeg's RGB of the colour frame; chroma upsampling may differ by a few levels.
  const int expected[2][5] = {{640, 360, 118, 102, 101}, {100, 100, 136, 146, 125}};
  for (const auto& e : expected) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(capture->color->at(e[0], e[1], c), e[2 + c], 6);
  }
  EXPECT_FALSE(reader.Next().has_value());
  const AzureReadStats& stats = reader.stats();
  EXPECT_EQ(stats.captures, 1);
  EXPECT_EQ(stats.color_frames, 1);
  EXPECT_EQ(stats.depth_frames, 1);
  EXPECT_EQ(stats.ir_frames, 1);
  EXPECT_EQ(stats.color_without_depth, 0);
  EXPECT_EQ(stats.dropped_depth, 0);
}

TEST(AzureKinectReader, ReadsDepthAloneWhenColourIsOff) {
  AzureReaderOptions options;
  options.read_color = false;
  AzureKinectReader reader(Recording(), options);
  std::optional<AzureCapture> capture = reader.Next();
  ASSERT_TRUE(capture.has_value());
  EXPECT_FALSE(capture->color.has_value());
  ASSERT_TRUE(capture->depth.has_value());
  EXPECT_EQ(capture->depth->at(320, 288), 1939);
}

// The first `bytes` of the recording, written to the test's folder.
fs::path TruncatedCopy(size_t bytes) {
  const std::string data = test::ReadText(Recording());
  const fs::path path = test::TempDir() / "truncated.mkv";
  test::WriteText(path, data.substr(0, std::min(bytes, data.size())));
  return path;
}

// Reads every capture; the InputError's message, or "" when none.
std::string ReadAllError(const fs::path& path) {
  return test::ErrorOf<InputError>([&] {
    AzureKinectReader reader(path);
    while (reader.Next()) {
    }
  });
}

TEST(AzureKinectReader, ATruncatedFileIsAnErrorNamingTheFileAndFrame) {
  const size_t size = fs::file_size(Recording());
  for (const double share : {0.05, 0.2, 0.5, 0.9, 0.999}) {
    const fs::path path = TruncatedCopy(static_cast<size_t>(share * size));
    const std::string error = ReadAllError(path);
    SCOPED_TRACE(share);
    EXPECT_NE(error.find(path.string()), std::string::npos) << error;
    EXPECT_NE(error.find("truncated"), std::string::npos) << error;
  }
}

TEST(AzureKinectReader, ACorruptColourFrameIsAnErrorNamingTheFrame) {
  // The colour frame's JPEG headers (after its start-of-image marker) overwritten in a copy.
  std::string data = test::ReadText(Recording());
  const size_t jpeg = data.find("\xff\xd8\xff");
  ASSERT_NE(jpeg, std::string::npos);
  for (size_t i = jpeg + 2; i < jpeg + 600; ++i) data[i] = static_cast<char>(0xaa);
  const fs::path path = test::TempDir() / "corrupt.mkv";
  test::WriteText(path, data);
  const std::string error = ReadAllError(path);
  EXPECT_NE(error.find(path.string()), std::string::npos) << error;
  EXPECT_NE(error.find("COLOR frame 0"), std::string::npos) << error;
}

TEST(AzureKinectReader, AMissingCalibrationAttachmentIsAnError) {
  // The attachment's file name renamed in a copy: the file is otherwise intact.
  std::string data = test::ReadText(Recording());
  for (size_t at = data.find("calibration.json"); at != std::string::npos;
       at = data.find("calibration.json", at)) {
    data[at + 11] = 'X';
  }
  const fs::path path = test::TempDir() / "no_calibration.mkv";
  test::WriteText(path, data);
  const std::string error = test::ErrorOf<InputError>([&] { AzureKinectReader reader(path); });
  EXPECT_NE(error.find(path.string()), std::string::npos) << error;
  EXPECT_NE(error.find("calibration.json attachment"), std::string::npos) << error;
}

TEST(AzureKinectReader, AnUnsupportedColourFormatIsAnErrorNamingIt) {
  // The colour track's FourCC (MJPG, in its VFW header) made XVID in a copy.
  std::string data = test::ReadText(Recording());
  const size_t at = data.find("MJPG");
  ASSERT_NE(at, std::string::npos);
  data.replace(at, 4, "XVID");
  const fs::path path = test::TempDir() / "xvid.mkv";
  test::WriteText(path, data);
  const std::string error = test::ErrorOf<InputError>([&] { AzureKinectReader reader(path); });
  EXPECT_NE(error.find(path.string() + ": COLOR: expected colour in MJPEG, NV12, YUY2 or BGRA"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("XVID"), std::string::npos) << error;
  // Depth alone still reads.
  AzureReaderOptions depth_only;
  depth_only.read_color = false;
  AzureKinectReader reader(path, depth_only);
  EXPECT_TRUE(reader.Next().has_value());
}

TEST(AzureKinectReader, NotARecordingIsAnError) {
  const fs::path path = test::TempDir() / "notes.mkv";
  test::WriteText(path, "these are not video frames");
  EXPECT_NE(test::ErrorOf<InputError>([&] { AzureKinectReader reader(path); }).find(path.string()),
            std::string::npos);
  const fs::path missing = test::TempDir() / "missing.mkv";
  EXPECT_NE(test::ErrorOf<InputError>([&] { AzureKinectReader reader(missing); }).find("no such"),
            std::string::npos);
}

}  // namespace
}  // namespace simtree
