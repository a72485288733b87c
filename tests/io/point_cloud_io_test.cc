#include "simtree/io/point_cloud_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "test_util.h"

namespace simtree {
namespace {

using ::testing::HasSubstr;

std::string ErrorOf(const std::filesystem::path& path) {
  try {
    ReadPointCloud(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(PointCloudIo, ReadsTheRealScans) {
  PointCloudReadReport report;
  const auto cloud = ReadPointCloud(test::SharedData("real-scans/tree1.xyz"), &report);
  EXPECT_EQ(cloud.points_.size(), 11855u);
  EXPECT_EQ(report.dropped_non_finite, 0u);
  EXPECT_EQ(ReadPointCloud(test::SharedData("real-scans/rtwig_cloud.xyz")).points_.size(), 14667u);
}

TEST(PointCloudIo, DropsNonFinitePointsAndSaysWhere) {
  const auto dir = test::TempDir();
  test::WriteText(dir / "c.xyz", "1 2 3\n4 nan 6\n7,8,9\r\n# comment\n\n1 1 inf\n");
  PointCloudReadReport report;
  const auto cloud = ReadPointCloud(dir / "c.xyz", &report);
  ASSERT_EQ(cloud.points_.size(), 2u);
  EXPECT_EQ(cloud.points_[1], Eigen::Vector3d(7, 8, 9));
  EXPECT_EQ(report.dropped_non_finite, 2u);
  EXPECT_EQ(report.first_non_finite_line, 2);
}

TEST(PointCloudIo, BadFilesAreClearErrors) {
  const auto dir = test::TempDir();
  test::WriteText(dir / "empty.xyz", "");
  EXPECT_THAT(ErrorOf(dir / "empty.xyz"),
              HasSubstr("empty.xyz: expected points, the file has none"));
  test::WriteText(dir / "nan.xyz", "nan nan nan\nnan 1 2\n");
  EXPECT_THAT(ErrorOf(dir / "nan.xyz"), HasSubstr("every point has NaN or infinite coordinates"));
  test::WriteText(dir / "bad.xyz", "1 2 3\n4 five 6\n");
  EXPECT_THAT(ErrorOf(dir / "bad.xyz"), HasSubstr("bad.xyz: line 2: expected 3 numbers"));
  test::WriteText(dir / "short.xyz", "1 2 3\n4 5\n");
  EXPECT_THAT(ErrorOf(dir / "short.xyz"), HasSubstr("line 2: expected 3 numbers"));
  test::WriteText(dir / "empty.ply", "");
  EXPECT_THAT(ErrorOf(dir / "empty.ply"), HasSubstr("the file is empty"));
  test::WriteText(dir / "junk.ply", "ply\nformat ascii 1.0\nelement vertex 10\n");
  EXPECT_THAT(ErrorOf(dir / "junk.ply"), HasSubstr("junk.ply"));
  EXPECT_THAT(ErrorOf(dir / "c.e57"), HasSubstr("no such file"));
  test::WriteText(dir / "c.e57", "x");
  EXPECT_THAT(ErrorOf(dir / "c.e57"), HasSubstr("expected a point cloud ending in"));
  test::WriteText(dir / "c.las", "x");
  EXPECT_THAT(ErrorOf(dir / "c.las"), HasSubstr("c.las: expected a LAS header"));
}

TEST(PointCloudIo, PlyRoundTrip) {
  const auto dir = test::TempDir();
  open3d::geometry::PointCloud cloud;
  for (int i = 0; i < 100; ++i) cloud.points_.emplace_back(i * 0.01, -i * 0.02, 1.5);
  WritePointCloud(cloud, dir / "c.ply");
  const auto back = ReadPointCloud(dir / "c.ply");
  ASSERT_EQ(back.points_.size(), 100u);
  EXPECT_TRUE(back.points_[42].isApprox(cloud.points_[42]));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);  // no temporaries
}

}  // namespace
}  // namespace simtree
