#include "simtree/preprocessing/preprocess_view.h"

#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "preprocessing/option_fixtures.h"
#include "preprocessing_fixtures.h"
#include "simtree/core/error.h"

namespace simtree::preprocessing {
namespace {

open3d::geometry::PointCloud Scene(uint64_t seed) {
  open3d::geometry::PointCloud cloud;
  test::AddGround(cloud, 0.01, 0.004, seed);
  test::AddTrunk(cloud, 0.1, 2.5, 0.08, 1.5, 0.005, 0.002, seed + 1);
  // Sparse outliers in the air.
  std::mt19937_64 rng(seed + 2);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 40; ++i)
    cloud.points_.emplace_back(-1 + 2 * u(rng), -1 + u(rng), 1 + 3 * u(rng));
  return cloud;
}

TEST(Preprocess, FindsTheGroundAndItsNoise) {
  const auto ground = FindGroundPlane(Scene(1));
  ASSERT_TRUE(ground);
  // The plane y = 1.2, its normal towards the camera (-y).
  EXPECT_GT(ground->normal.dot(-Eigen::Vector3d::UnitY()), std::cos(0.5 * std::numbers::pi / 180));
  EXPECT_NEAR(ground->offset, 1.2, 0.003);
  EXPECT_NEAR(ground->noise_m, 0.004, 0.001);
}

TEST(Preprocess, KeepsTheTreeAndRemovesGroundAndOutliers) {
  const auto scene = Scene(2);
  const PreprocessResult r = PreprocessView(scene);
  ASSERT_TRUE(r.ground);
  EXPECT_NEAR(r.up.dot(-Eigen::Vector3d::UnitY()), 1.0, 1e-4);
  EXPECT_NEAR(r.point_spacing_m, 0.005, 0.002);
  EXPECT_NEAR(r.voxel_size_m, 2.5 * r.point_spacing_m, 1e-12);
  EXPECT_GT(r.DownsampleRemovedShare(), 0.3);
  EXPECT_GT(r.cloud.points_.size(), 500u);
  for (const auto& p : r.cloud.points_) {
    // Every point kept is on the trunk: near its axis (a ground point just above the noise band
    // may join the trunk's foot), above the ground band.
    EXPECT_LT(std::hypot(p.x() - 0.1, p.z() - 2.5), 0.08 + 0.03) << p.transpose();
    EXPECT_LT(p.y(), 1.2 - 0.005);
  }
  EXPECT_EQ(r.input_points, scene.points_.size());
  EXPECT_GT(r.ground_points, 20000u);
}

TEST(Preprocess, WithoutGroundUpIsTheCamerasMinusY) {
  open3d::geometry::PointCloud cloud;
  test::AddTrunk(cloud, 0.0, 2.0, 0.08, 1.5, 0.005, 0.002, 3);
  const PreprocessResult r = PreprocessView(cloud);
  EXPECT_FALSE(r.ground);
  EXPECT_EQ(r.up, -Eigen::Vector3d::UnitY());
  EXPECT_GT(r.cloud.points_.size(), 500u);
}

TEST(Preprocess, IsDeterministic) {
  const auto a = PreprocessView(Scene(4));
  const auto b = PreprocessView(Scene(4));
  ASSERT_EQ(a.cloud.points_.size(), b.cloud.points_.size());
  for (size_t i = 0; i < a.cloud.points_.size(); ++i) {
    EXPECT_EQ(a.cloud.points_[i], b.cloud.points_[i]);
  }
}

TEST(Preprocess, BadInputsAreClearErrors) {
  open3d::geometry::PointCloud empty;
  EXPECT_THROW(PreprocessView(empty, {}, "view_00"), InputError);
  open3d::geometry::PointCloud nan_cloud;
  for (int i = 0; i < 10; ++i) {
    nan_cloud.points_.emplace_back(std::numeric_limits<double>::quiet_NaN(), 0, 1);
  }
  try {
    PreprocessView(nan_cloud, {}, "view_03");
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("view_03"), std::string::npos) << e.what();
  }
  open3d::geometry::PointCloud only_ground;
  test::AddGround(only_ground, 0.02, 0.003, 5);
  EXPECT_THROW(PreprocessView(only_ground, {}, "view_01"), InputError);
}

TEST(Preprocess, NonsenseOptionsAreRefusedBeforeAnyWork) {
  using Options = PreprocessOptions;
  auto refused = [](auto change) { return test::RefusedFieldAfter<Options>(change); };
  EXPECT_EQ(test::RefusedField(Options{}), "");
  EXPECT_EQ(refused([](Options& o) { o.voxel_size_m = -0.01; }), "voxel_size_m");
  EXPECT_EQ(refused([](Options& o) { o.min_ground_share = 1.5; }), "min_ground_share");
  EXPECT_EQ(
      refused([](Options& o) { o.max_ground_tilt_deg = std::numeric_limits<double>::quiet_NaN(); }),
      "max_ground_tilt_deg");
  EXPECT_EQ(refused([](Options& o) { o.ground_sample_points = 0; }), "ground_sample_points");
  // The options are named, not the (empty) cloud.
  Options options;
  options.cluster_link_factor = 0;
  try {
    PreprocessView(open3d::geometry::PointCloud(), options, "view_00");
    FAIL() << "a zero cluster link accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "options");
  }
}

}  // namespace
}  // namespace simtree::preprocessing
