// LAS files written by the test-support writer (tests/support/las_writer.h, after the ASPRS
// specification's header layout): versions 1.2-1.4, point formats 0-3 and 6-8, scale and offset,
// colour, variable length records before the points, extra bytes per record; and the files simtree
// refuses.

#include <cstring>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/cloud_read_error.h"
#include "simtree/io/las_io.h"
#include "simtree/io/point_cloud_io.h"
#include "support/las_writer.h"
#include "test_util.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using test::LasBytes;
using test::LasPoint;
using test::LasSpec;
using test::WriteLas;

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

TEST(LasIo, RefusedFilesSayWhy) {
  const fs::path dir = test::TempDir();
  // A format-0 file relabelled format 4 (waveforms): the format alone decides.
  std::string waveform = LasBytes(LasSpec{}, kPoints);
  waveform[test::kLasPointFormatAt] = 4;
  test::WriteText(dir / "waveform.las", waveform);
  EXPECT_THAT(test::CloudReadError(dir / "waveform.las"),
              HasSubstr("waveform.las: point data format: point format 4 is not read"));

  std::string laz = LasBytes(LasSpec{}, kPoints);
  laz[test::kLasPointFormatAt] = static_cast<char>(0x80 | 3);  // how LAZ marks compressed format 3
  test::WriteText(dir / "renamed.las", laz);
  EXPECT_THAT(test::CloudReadError(dir / "renamed.las"),
              HasSubstr("LAZ (compressed LAS) is not read"));
  test::WriteText(dir / "scan.laz", laz);
  EXPECT_THAT(test::CloudReadError(dir / "scan.laz"), HasSubstr("laszip -i scan.laz -o scan.las"));

  std::string truncated = LasBytes(LasSpec{}, kPoints);
  truncated.resize(truncated.size() - 5);
  test::WriteText(dir / "truncated.las", truncated);
  EXPECT_THAT(test::CloudReadError(dir / "truncated.las"),
              HasSubstr("the header says 2 points of 20 bytes from byte 227, the file holds 1"));

  std::string short_record = LasBytes(LasSpec{}, kPoints);
  short_record[test::kLasPointFormatAt] = 2;  // colour formats need 26 bytes, the records have 20
  test::WriteText(dir / "short.las", short_record);
  EXPECT_THAT(test::CloudReadError(dir / "short.las"),
              HasSubstr("expected at least 26 bytes for point format 2"));

  std::string not_las = LasBytes(LasSpec{}, kPoints);
  not_las[0] = 'X';
  test::WriteText(dir / "not.las", not_las);
  EXPECT_THAT(test::CloudReadError(dir / "not.las"), HasSubstr("not a LAS file"));

  LasSpec zero_scale;
  zero_scale.scale[1] = 0;
  WriteLas(dir / "scale.las", zero_scale, kPoints);
  EXPECT_THAT(test::CloudReadError(dir / "scale.las"), HasSubstr("y scale factor and offset"));

  WriteLas(dir / "empty.las", LasSpec{}, {});
  EXPECT_THAT(test::CloudReadError(dir / "empty.las"),
              HasSubstr("expected points, the file has none"));
}

}  // namespace
}  // namespace simtree
