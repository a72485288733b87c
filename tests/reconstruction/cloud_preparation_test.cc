#include "simtree/reconstruction/detail/cloud_preparation.h"

#include <cmath>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "reconstruction/reconstruction_fixtures.h"
#include "simtree/core/error.h"

namespace simtree::reconstruction {
namespace {

using ::testing::HasSubstr;

std::vector<Eigen::Vector3d> Trunk() {
  return test::CylinderPoints({0, 0, 0}, {0, 0, 1}, 2.0, 0.1, 0.02);
}

std::string MessageOf(const std::vector<Eigen::Vector3d>& points,
                      const CloudPreparationOptions& options = {}) {
  try {
    PrepareCloud(points, "scan.xyz", options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CloudPreparation, KeepsAGoodCloudAsItIs) {
  const auto points = Trunk();
  const PreparedCloud prepared = PrepareCloud(points, "scan.xyz");
  EXPECT_EQ(prepared.points.size(), points.size());
  EXPECT_EQ(prepared.dropped_non_finite, 0u);
  EXPECT_EQ(prepared.dropped_duplicates, 0u);
  EXPECT_TRUE(prepared.warnings.empty());
  EXPECT_NEAR(prepared.extent.z(), 2.0, 0.01);
}

TEST(CloudPreparation, RefusesAnEmptyOrAllNanCloud) {
  EXPECT_THAT(MessageOf({}), HasSubstr("scan.xyz: the cloud has no points"));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(MessageOf({{nan, 0, 0}, {0, nan, 1}}), HasSubstr("no point has finite coordinates"));
}

TEST(CloudPreparation, DropsNanAndInfinitePointsWithAWarning) {
  auto points = Trunk();
  const size_t good = points.size();
  points.insert(points.begin() + 5, {std::numeric_limits<double>::quiet_NaN(), 0, 0});
  points.push_back({0, std::numeric_limits<double>::infinity(), 0});
  const PreparedCloud prepared = PrepareCloud(points, "scan.xyz");
  EXPECT_EQ(prepared.points.size(), good);
  EXPECT_EQ(prepared.dropped_non_finite, 2u);
  ASSERT_EQ(prepared.warnings.size(), 1u);
  EXPECT_THAT(prepared.warnings[0], HasSubstr("dropped 2 points with NaN"));
  EXPECT_THAT(prepared.warnings[0], HasSubstr("point 5"));
}

TEST(CloudPreparation, DropsDuplicatedPointsAndSaysWhenTheScanWasMergedTwice) {
  auto points = Trunk();
  const size_t good = points.size();
  auto twice = points;
  twice.insert(twice.end(), points.begin(), points.end());
  const PreparedCloud prepared = PrepareCloud(twice, "scan.xyz");
  EXPECT_EQ(prepared.points.size(), good);
  EXPECT_EQ(prepared.dropped_duplicates, good);
  ASSERT_EQ(prepared.warnings.size(), 1u);
  EXPECT_THAT(prepared.warnings[0], HasSubstr("merged twice"));
  // A few copies: counted, no guess about merging.
  points.push_back(points[3]);
  points.push_back(points[3] + Eigen::Vector3d(1e-9, 0, 0));  // a float round trip of it
  const PreparedCloud few = PrepareCloud(points, "scan.xyz");
  EXPECT_EQ(few.dropped_duplicates, 2u);
  EXPECT_THAT(few.warnings[0], ::testing::Not(HasSubstr("merged twice")));
}

TEST(CloudPreparation, SaysACloudInMillimetresIsInMillimetres) {
  auto points = Trunk();
  for (auto& p : points) p *= 1000.0;
  const std::string message = MessageOf(points);
  EXPECT_THAT(message, HasSubstr("scan.xyz: units:"));
  EXPECT_THAT(message, HasSubstr("looks like millimetres"));
  EXPECT_THAT(message, HasSubstr("--scale 0.001"));
  // ... and reads it with the scale it suggests.
  const PreparedCloud prepared = PrepareCloud(points, "scan.xyz", {.scale = 0.001});
  EXPECT_NEAR(prepared.extent.z(), 2.0, 0.01);
  // Centimetres are recognised too.
  for (auto& p : points) p *= 0.1;
  EXPECT_THAT(MessageOf(points), HasSubstr("looks like centimetres"));
}

TEST(CloudPreparation, RefusesACloudWithNoVerticalStructure) {
  std::vector<Eigen::Vector3d> lawn;
  for (int i = 0; i < 50; ++i) {
    for (int j = 0; j < 50; ++j) lawn.push_back({0.05 * i, 0.05 * j, 0.001 * ((i * j) % 7)});
  }
  EXPECT_THAT(MessageOf(lawn), HasSubstr("no vertical structure"));
  EXPECT_THAT(MessageOf(lawn), HasSubstr("Z up"));
  // A tree lying on its side (Y up) is flat in Z as well.
  auto lying = Trunk();
  for (auto& p : lying) p = Eigen::Vector3d(p.z(), p.x(), 0.1 * p.y());
  EXPECT_THAT(MessageOf(lying), HasSubstr("no vertical structure"));
}

TEST(CloudPreparation, RefusesBadOptionsBeforeLookingAtThePoints) {
  EXPECT_EQ(MessageOf(Trunk(), {.scale = -1.0}), "options: scale: expected > 0, got -1");
  EXPECT_THAT(MessageOf({}, {.scale = std::nan("")}), HasSubstr("scale: expected > 0, got nan"));
  EXPECT_THAT(MessageOf(Trunk(), {.max_height_m = 60.0, .min_height_m = 70.0}),
              HasSubstr("max_height_m: expected >= min_height_m (70), got 60"));
  EXPECT_THAT(MessageOf(Trunk(), {.extent_trim = 0.7}),
              HasSubstr("extent_trim: expected a value in [0, 0.5], got 0.7"));
}

TEST(CloudPreparation, IgnoresAFewFarOutliersWhenMeasuring) {
  auto points = Trunk();
  points.push_back({0, 0, 500.0});  // one stray return far above
  const PreparedCloud prepared = PrepareCloud(points, "scan.xyz");
  EXPECT_NEAR(prepared.extent.z(), 2.0, 0.05);
}

}  // namespace
}  // namespace simtree::reconstruction
