#include "simtree/reconstruction/detail/point_index.h"

#include <gtest/gtest.h>

namespace simtree::reconstruction {
namespace {

TEST(PointIndex, AnswersNearestRadiusAndHybridQueries) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 10; ++i) points.push_back({0.1 * i, 0, 0});
  const PointIndex index(points);
  std::vector<int> near;
  std::vector<double> d2;
  index.Nearest({0.32, 0, 0}, 2, near, d2);
  ASSERT_EQ(near.size(), 2u);
  EXPECT_EQ(near[0], 3);
  EXPECT_EQ(near[1], 4);
  EXPECT_NEAR(d2[0], 0.02 * 0.02, 1e-12);
  index.WithinRadius({0.0, 0, 0}, 0.25, near, d2);
  ASSERT_EQ(near.size(), 3u);
  EXPECT_EQ(near[0], 0);
  EXPECT_EQ(near[2], 2);
  index.NearestWithin({0.0, 0, 0}, 0.55, 2, near, d2);
  EXPECT_EQ(near.size(), 2u);
  const PointIndex empty(std::vector<Eigen::Vector3d>{});
  empty.Nearest({0, 0, 0}, 3, near, d2);
  EXPECT_TRUE(near.empty());
}

}  // namespace
}  // namespace simtree::reconstruction
