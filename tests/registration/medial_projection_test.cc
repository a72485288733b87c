#include "simtree/registration/medial_projection.h"

#include <cmath>

#include <gtest/gtest.h>

#include "scan/scan_fixtures.h"

namespace simtree {
namespace {

TEST(MedialProjection, HalfCylinderPointsMoveOntoTheAxis) {
  open3d::geometry::PointCloud cloud;
  test::AddTrunk(cloud, 0.0, 2.0, 0.06, 0.6, 0.006, 0.0, 1);
  cloud.EstimateNormals(open3d::geometry::KDTreeSearchParamHybrid(0.025, 30));
  cloud.OrientNormalsTowardsCameraLocation(Eigen::Vector3d::Zero());
  const open3d::geometry::KDTreeFlann tree(cloud);
  std::vector<size_t> indices;
  for (size_t i = 0; i < cloud.points_.size(); ++i) {
    // Away from the ends, whose neighbourhoods are one-sided along the axis.
    if (cloud.points_[i].y() < 1.1 && cloud.points_[i].y() > 0.7) indices.push_back(i);
  }
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

TEST(MedialProjection, WithoutNormalsPointsStay) {
  open3d::geometry::PointCloud cloud;
  test::AddTrunk(cloud, 0.0, 2.0, 0.06, 0.3, 0.01, 0.0, 1);
  const open3d::geometry::KDTreeFlann tree(cloud);
  const auto projected = ProjectToMedialAxes(cloud, tree, {0, 5, 9});
  EXPECT_EQ(projected[1], cloud.points_[5]);
}

}  // namespace
}  // namespace simtree
