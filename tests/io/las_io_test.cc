// LAS files written by the test's own writer (below, after the ASPRS specification's header
// layout): versions 1.2-1.4, point formats 0-3 and 6-8, scale and offset, colour, variable length
// records before the points, extra bytes per record; and the files simtree refuses.

#include <cstring>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/io/las_io.h"
#include "simtree/io/point_cloud_io.h"
#include "test_util.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

struct LasPoint {
  int32_t x, y, z;
  uint16_t r = 0, g = 0, b = 0;
};

struct LasSpec {
  int minor = 2;
  int format = 0;
  int extra_bytes = 0;  // after the format's fields
  int vlr_bytes = 0;    // between the header and the points
  double scale[3] = {0.001, 0.001, 0.01};
  double offset[3] = {100, 200, 10};
};

template <typename T>
void Put(std::string& bytes, size_t at, T value) {
  std::memcpy(bytes.data() + at, &value, sizeof(T));
}

int BaseLength(int format) {
  const int lengths[] = {20, 28, 26, 34, 0, 0, 30, 36, 38};
  return lengths[format];
}
int ColorOffset(int format) {
  const int offsets[] = {-1, -1, 20, 28, -1, -1, -1, 30, 30};
  return offsets[format];
}

std::string LasBytes(const LasSpec& spec, const std::vector<LasPoint>& points) {
  const int header = spec.minor >= 4 ? 375 : spec.minor == 3 ? 235 : 227;
  const int record = BaseLength(spec.format) + spec.extra_bytes;
  std::string bytes(header + spec.vlr_bytes + record * points.size(), '\0');
  std::memcpy(bytes.data(), "LASF", 4);
  bytes[24] = 1;
  bytes[25] = static_cast<char>(spec.minor);
  Put<uint16_t>(bytes, 94, static_cast<uint16_t>(header));
  Put<uint32_t>(bytes, 96, static_cast<uint32_t>(header + spec.vlr_bytes));
  Put<uint32_t>(bytes, 100, spec.vlr_bytes > 0 ? 1 : 0);
  bytes[104] = static_cast<char>(spec.format);
  Put<uint16_t>(bytes, 105, static_cast<uint16_t>(record));
  // LAS 1.4 keeps the legacy count 0 for formats 6-10 and the count in a 64-bit field.
  if (spec.format < 6) Put<uint32_t>(bytes, 107, static_cast<uint32_t>(points.size()));
  if (spec.minor >= 4) Put<uint64_t>(bytes, 247, points.size());
  for (int k = 0; k < 3; ++k) {
    Put<double>(bytes, 131 + 8 * k, spec.scale[k]);
    Put<double>(bytes, 155 + 8 * k, spec.offset[k]);
  }
  for (size_t i = 0; i < points.size(); ++i) {
    const size_t at = header + spec.vlr_bytes + i * record;
    Put<int32_t>(bytes, at, points[i].x);
    Put<int32_t>(bytes, at + 4, points[i].y);
    Put<int32_t>(bytes, at + 8, points[i].z);
    Put<uint16_t>(bytes, at + 12, 7777);  // intensity: must not leak into anything
    if (ColorOffset(spec.format) >= 0) {
      Put<uint16_t>(bytes, at + ColorOffset(spec.format), points[i].r);
      Put<uint16_t>(bytes, at + ColorOffset(spec.format) + 2, points[i].g);
      Put<uint16_t>(bytes, at + ColorOffset(spec.format) + 4, points[i].b);
    }
  }
  return bytes;
}

fs::path WriteLas(const fs::path& path, const LasSpec& spec, const std::vector<LasPoint>& points) {
  test::WriteText(path, LasBytes(spec, points));
  return path;
}

const std::vector<LasPoint> kPoints = {{0, 0, 0, 255, 0, 0}, {1500, -2500, 123, 0, 128, 255}};

TEST(LasIo, AppliesScaleAndOffsetInEveryVersionAndFormat) {
  const fs::path dir = test::TempDir();
  for (int minor : {2, 3, 4}) {
    for (int format : {0, 1, 2, 3, 6, 7, 8}) {
      if (format >= 6 && minor < 4) continue;
      LasSpec spec;
      spec.minor = minor;
      spec.format = format;
      spec.extra_bytes = 3;
      spec.vlr_bytes = 54;
      const fs::path path =
          WriteLas(dir / fmt::format("v1{}_f{}.las", minor, format), spec, kPoints);
      LasReadReport report;
      const auto cloud = ReadLas(path, &report);
      SCOPED_TRACE(path.filename().string());
      ASSERT_EQ(cloud.points_.size(), 2u);
      EXPECT_EQ(report.version_minor, minor);
      EXPECT_EQ(report.point_format, format);
      EXPECT_NEAR(cloud.points_[0].x(), 100.0, 1e-12);
      EXPECT_NEAR(cloud.points_[1].x(), 101.5, 1e-12);
      EXPECT_NEAR(cloud.points_[1].y(), 197.5, 1e-12);
      EXPECT_NEAR(cloud.points_[1].z(), 11.23, 1e-12);
      const bool color = format == 2 || format == 3 || format == 7 || format == 8;
      EXPECT_EQ(report.has_color, color);
      ASSERT_EQ(cloud.HasColors(), color);
      if (color) {  // 8-bit values stored in 16-bit fields
        EXPECT_DOUBLE_EQ(cloud.colors_[0].x(), 1.0);
        EXPECT_DOUBLE_EQ(cloud.colors_[1].y(), 128.0 / 255);
      }
    }
  }
}

TEST(LasIo, A14FileWithOnlyTheLegacyCountIsRead) {
  LasSpec spec;
  spec.minor = 4;
  std::string bytes = LasBytes(spec, kPoints);
  std::memset(bytes.data() + 247, 0, 8);  // the 64-bit count left empty
  const fs::path path = test::TempDir() / "legacy.las";
  test::WriteText(path, bytes);
  EXPECT_EQ(ReadLas(path).points_.size(), 2u);
}

TEST(LasIo, SixteenBitColourAndTheCloudReaderFront) {
  const fs::path dir = test::TempDir();
  LasSpec spec;
  spec.format = 3;
  const fs::path path = WriteLas(dir / "scan.LAS", spec, {{0, 0, 0, 65535, 32768, 0}});
  EXPECT_TRUE(IsPointCloudFile(path));
  PointCloudReadReport report;
  const auto cloud = ReadPointCloud(path, &report);
  EXPECT_EQ(report.points, 1u);
  EXPECT_DOUBLE_EQ(cloud.colors_[0].x(), 1.0);
  EXPECT_NEAR(cloud.colors_[0].y(), 0.5, 1e-4);
}

std::string ErrorOf(const fs::path& path) {
  return test::ErrorOf([&] { ReadPointCloud(path); });
}

TEST(LasIo, RefusedFilesSayWhy) {
  const fs::path dir = test::TempDir();
  // A format-0 file relabelled format 4 (waveforms): the format alone decides.
  std::string waveform = LasBytes(LasSpec{}, kPoints);
  waveform[104] = 4;
  test::WriteText(dir / "waveform.las", waveform);
  EXPECT_THAT(ErrorOf(dir / "waveform.las"),
              HasSubstr("waveform.las: point data format: point format 4 is not read"));

  std::string laz = LasBytes(LasSpec{}, kPoints);
  laz[104] = static_cast<char>(0x80 | 3);  // how LAZ marks compressed format 3
  test::WriteText(dir / "renamed.las", laz);
  EXPECT_THAT(ErrorOf(dir / "renamed.las"), HasSubstr("LAZ (compressed LAS) is not read"));
  test::WriteText(dir / "scan.laz", laz);
  EXPECT_THAT(ErrorOf(dir / "scan.laz"), HasSubstr("laszip -i scan.laz -o scan.las"));

  std::string truncated = LasBytes(LasSpec{}, kPoints);
  truncated.resize(truncated.size() - 5);
  test::WriteText(dir / "truncated.las", truncated);
  EXPECT_THAT(ErrorOf(dir / "truncated.las"),
              HasSubstr("the header says 2 points of 20 bytes from byte 227, the file holds 1"));

  std::string short_record = LasBytes(LasSpec{}, kPoints);
  short_record[104] = 2;  // colour formats need 26 bytes, the records have 20
  test::WriteText(dir / "short.las", short_record);
  EXPECT_THAT(ErrorOf(dir / "short.las"),
              HasSubstr("expected at least 26 bytes for point format 2"));

  std::string not_las = LasBytes(LasSpec{}, kPoints);
  not_las[0] = 'X';
  test::WriteText(dir / "not.las", not_las);
  EXPECT_THAT(ErrorOf(dir / "not.las"), HasSubstr("not a LAS file"));

  LasSpec zero_scale;
  zero_scale.scale[1] = 0;
  WriteLas(dir / "scale.las", zero_scale, kPoints);
  EXPECT_THAT(ErrorOf(dir / "scale.las"), HasSubstr("y scale factor and offset"));

  WriteLas(dir / "empty.las", LasSpec{}, {});
  EXPECT_THAT(ErrorOf(dir / "empty.las"), HasSubstr("expected points, the file has none"));
}

}  // namespace
}  // namespace simtree
