#include "simtree/registration/detail/medial_projection.h"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "preprocessing/option_fixtures.h"
#include "preprocessing/preprocessing_fixtures.h"

namespace simtree::registration {
namespace {

// Normals over `radius`, turned towards a camera at the origin, as a view's are.
void NormalsSeenFromTheOrigin(open3d::geometry::PointCloud& cloud, double radius) {
  cloud.EstimateNormals(open3d::geometry::KDTreeSearchParamHybrid(radius, 30));
  cloud.OrientNormalsTowardsCameraLocation(Eigen::Vector3d::Zero());
}

// The points of `cloud` with low < y < high.
std::vector<size_t> PointsBetween(const open3d::geometry::PointCloud& cloud, double low,
                                  double high) {
  std::vector<size_t> indices;
  for (size_t i = 0; i < cloud.points_.size(); ++i) {
    if (cloud.points_[i].y() < high && cloud.points_[i].y() > low) indices.push_back(i);
  }
  return indices;
}

TEST(MedialProjection, HalfCylinderPointsMoveOntoTheAxis) {
  open3d::geometry::PointCloud cloud;
  test::AddTrunk(cloud, 0.0, 2.0, 0.06, 0.6, 0.006, 0.0, 1);
  NormalsSeenFromTheOrigin(cloud, 0.025);
  const open3d::geometry::KDTreeFlann tree(cloud);
  // Away from the ends, whose neighbourhoods are one-sided along the axis.
  const std::vector<size_t> indices = PointsBetween(cloud, 0.7, 1.1);
  const auto projected = ProjectToMedialAxes(cloud, tree, indices);
  double before = 0, after = 0;
  for (size_t k = 0; k < indices.size(); ++k) {
    const Eigen::Vector3d& p = cloud.points_[indices[k]];
    before += std::hypot(p.x(), p.z() - 2.0);
    after += std::hypot(projected[k].x(), projected[k].z() - 2.0);
    EXPECT_NEAR(projected[k].y(), p.y(), 0.01);  // along the axis it stays
  }
  before /= indices.size();
  after /= indices.size();
  EXPECT_NEAR(before, 0.06, 1e-6);
  EXPECT_LT(after, 0.012) << "mean distance to the axis after projection";
}

TEST(MedialProjection, ThinBranchAxisFromItsSilhouetteDoesNotLagTowardsTheCamera) {
  // A 2 cm branch seen from one side, normals over 4.6 cm (as a view's: 3 point spacings), wider
  // than the branch: they turn towards the camera and their lines barely meet, so where they
  // meet is off the axis along the line of sight (on the synthetic views, short of it by 5-10 mm;
  // here, far behind it). The silhouette (the branch's width across the line of sight) puts the
  // points on the axis.
  // Seen from the origin, with the depth noise along the line of sight (a time-of-flight
  // sensor's), 1.2 cm apart.
  open3d::geometry::PointCloud cloud;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.002);
  const double facing = std::atan2(-0.3, -2.0);
  for (double y = 1.2; y >= 0.6; y -= 0.012) {
    for (double a = facing - 1.4; a <= facing + 1.4; a += 0.6) {
      const Eigen::Vector3d p(0.3 + 0.02 * std::sin(a), y, 2.0 + 0.02 * std::cos(a));
      cloud.points_.push_back(p + noise(rng) * p.normalized());
    }
  }
  NormalsSeenFromTheOrigin(cloud, 0.046);
  const open3d::geometry::KDTreeFlann tree(cloud);
  const std::vector<size_t> indices = PointsBetween(cloud, 0.8, 1.0);
  ASSERT_GT(indices.size(), 50u);
  // Towards the camera (at the origin) from the axis, and distance to it, on average.
  const Eigen::Vector3d axis_point(0.3, 0.0, 2.0);
  const Eigen::Vector3d towards = -Eigen::Vector3d(0.3, 0.0, 2.0).normalized();
  auto lag = [&](const std::vector<Eigen::Vector3d>& projected, double& off_axis) {
    double sum = 0;
    off_axis = 0;
    for (const Eigen::Vector3d& p : projected) {
      Eigen::Vector3d d = p - axis_point;
      d.y() = 0;
      sum += d.dot(towards);
      off_axis += d.norm();
    }
    off_axis /= projected.size();
    return sum / projected.size();
  };
  MedialProjectionOptions normal_lines;
  double normal_off = 0, silhouette_off = 0;
  const double normal_lag =
      lag(ProjectToMedialAxes(cloud, tree, indices, normal_lines), normal_off);
  MedialProjectionOptions silhouette;
  silhouette.silhouette = true;
  const double silhouette_lag =
      lag(ProjectToMedialAxes(cloud, tree, indices, silhouette), silhouette_off);
  EXPECT_GT(std::abs(normal_lag), 0.01) << "the normal lines' error this test guards against";
  EXPECT_LT(std::abs(silhouette_lag), 0.004);
  EXPECT_LT(silhouette_off, 0.007);
  EXPECT_LT(silhouette_off, 0.2 * normal_off);
}

TEST(MedialProjection, ThickTrunkKeepsTheNormalLinesButAlongItsEdges) {
  // A 12 cm trunk, 1.5 cm apart, seen from the origin: wider than the neighbourhood (8 cm), so
  // the points facing the camera keep the normal lines' axis points. Along the visible edges the
  // neighbourhood is a narrow strip, whose inner edge is where the neighbourhood ends, and the
  // silhouette takes those points (a known weakness, docs/registration.md): a tighter test of
  // the edges measured worse on the synthetic views.
  open3d::geometry::PointCloud cloud;
  test::AddTrunk(cloud, 0.0, 2.5, 0.12, 0.8, 0.015, 0.0, 1);
  NormalsSeenFromTheOrigin(cloud, 0.046);
  const open3d::geometry::KDTreeFlann tree(cloud);
  std::vector<size_t> facing, edges;
  for (size_t i = 0; i < cloud.points_.size(); ++i) {
    const Eigen::Vector3d& p = cloud.points_[i];
    if (p.y() > 1.0 || p.y() < 0.6) continue;
    (std::abs(p.x()) < 0.12 * std::sin(45 * std::numbers::pi / 180) ? facing : edges).push_back(i);
  }
  MedialProjectionOptions silhouette;
  silhouette.silhouette = true;
  MedialProjectionOptions normal_lines = silhouette;
  normal_lines.silhouette = false;
  auto differing = [&](const std::vector<size_t>& indices) {
    const auto a = ProjectToMedialAxes(cloud, tree, indices, silhouette);
    const auto b = ProjectToMedialAxes(cloud, tree, indices, normal_lines);
    int count = 0;
    for (size_t k = 0; k < indices.size(); ++k) count += a[k] != b[k];
    return count;
  };
  ASSERT_GT(facing.size(), 100u);
  EXPECT_EQ(differing(facing), 0);
  EXPECT_LT(differing(edges), static_cast<int>(edges.size()));
}

TEST(MedialProjection, WithoutNormalsPointsStay) {
  open3d::geometry::PointCloud cloud;
  test::AddTrunk(cloud, 0.0, 2.0, 0.06, 0.3, 0.01, 0.0, 1);
  const open3d::geometry::KDTreeFlann tree(cloud);
  const auto projected = ProjectToMedialAxes(cloud, tree, {0, 5, 9});
  EXPECT_EQ(projected[1], cloud.points_[5]);
}

TEST(MedialProjection, NonsenseOptionsAreRefused) {
  using test::RefusedField;
  EXPECT_EQ(RefusedField(MedialProjectionOptions{}), "");
  EXPECT_EQ(RefusedField(MedialProjectionOptions{.neighbourhood_m = -0.08}), "neighbourhood_m");
  EXPECT_EQ(RefusedField(MedialProjectionOptions{.silhouette_containment = 2}),
            "silhouette_containment");
}

}  // namespace
}  // namespace simtree::registration
