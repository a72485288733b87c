// Clouds too large to hold: a header claiming 50 million points is refused before anything is
// allocated, whatever bytes follow it, with a message that says to thin the cloud (issue 27 part 4:
// never an out-of-memory kill). The limit itself is checked small on a real file.

#include <cstring>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/cloud_read_error.h"
#include "simtree/io/detail/cloud_header_check.h"
#include "simtree/io/point_cloud_io.h"
#include "support/las_writer.h"
#include "test_util.h"

namespace simtree {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::HasSubstr;

const auto kRefusedAsTooLarge = AllOf(HasSubstr("50000000 points or more"),
                                      HasSubstr("at most 20000000"), HasSubstr("thin the cloud"));

TEST(PointCloudLimits, FiftyMillionPointHeadersAreRefusedBeforeReading) {
  const fs::path dir = test::TempDir();
  // A few real points after each header: the count is what is refused, not missing data.
  const std::string xyz(3 * 4 * 5, '\0');
  test::WriteText(dir / "big.ply",
                  "ply\nformat binary_little_endian 1.0\nelement vertex 50000000\n"
                  "property float x\nproperty float y\nproperty float z\nend_header\n" +
                      xyz);
  EXPECT_THAT(test::CloudReadError(dir / "big.ply"),
              AllOf(HasSubstr("big.ply: header line 3"), kRefusedAsTooLarge));
  test::WriteText(dir / "big.pcd",
                  "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                  "WIDTH 50000000\nHEIGHT 1\nPOINTS 50000000\nDATA binary\n" +
                      xyz);
  EXPECT_THAT(test::CloudReadError(dir / "big.pcd"),
              AllOf(HasSubstr("big.pcd: header line 9"), kRefusedAsTooLarge));
  std::string las = test::LasBytes({}, {{0, 0, 0}, {1, 1, 1}});
  const uint32_t claim = 50'000'000;
  std::memcpy(las.data() + test::kLasLegacyCountAt, &claim, 4);
  test::WriteText(dir / "big.las", las);
  EXPECT_THAT(test::CloudReadError(dir / "big.las"),
              AllOf(HasSubstr("big.las: number of point records"), kRefusedAsTooLarge));
}

TEST(PointCloudLimits, TheLimitHoldsOnARealFile) {
  const fs::path dir = test::TempDir();
  open3d::geometry::PointCloud cloud;
  for (int i = 0; i < 30; ++i) cloud.points_.emplace_back(0.01 * i, 0, 1);
  WritePointCloud(cloud, dir / "c.ply");
  WritePointCloud(cloud, dir / "c.pcd");
  for (const char* name : {"c.ply", "c.pcd"}) {
    const fs::path path = dir / name;
    const auto check = [&](int64_t limit) {
      if (path.extension() == ".ply") {
        cloud_detail::CheckPlyHeader(path, limit);
      } else {
        cloud_detail::CheckPcdHeader(path, limit);
      }
    };
    EXPECT_NO_THROW(check(30)) << name;
    EXPECT_THAT(test::ErrorOf([&] { check(29); }),
                AllOf(HasSubstr("30 points or more"), HasSubstr("at most 29")))
        << name;
  }
  EXPECT_EQ(ReadPointCloud(dir / "c.ply").points_.size(), 30u);
}

}  // namespace
}  // namespace simtree
