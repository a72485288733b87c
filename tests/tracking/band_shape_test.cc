#include "simtree/tracking/detail/band_shape.h"
#include "simtree/eval/tracking_metrics.h"

#include <cmath>

#include <gtest/gtest.h>

#include "simtree/tracking/detail/band_model.h"

namespace simtree::tracking::detail {
namespace {

// A band seen from the side: a rectangle (half-length l px along `axis`, half-width r px),
// rasterised by each pixel's covered share (16 x 16 samples), pixels and weights as a blob's.
struct Drawn {
  std::vector<Eigen::Vector2d> points;
  std::vector<double> weights;
};
Drawn DrawBand(const Eigen::Vector2d& centre, const Eigen::Vector2d& axis, double l, double r) {
  const Eigen::Vector2d across(-axis.y(), axis.x());
  Drawn out;
  const int reach = static_cast<int>(std::ceil(l + r + 2));
  for (int y = int(centre.y()) - reach; y <= int(centre.y()) + reach; ++y) {
    for (int x = int(centre.x()) - reach; x <= int(centre.x()) + reach; ++x) {
      int inside = 0;
      for (int sy = 0; sy < 16; ++sy) {
        for (int sx = 0; sx < 16; ++sx) {
          const Eigen::Vector2d p(x - 0.5 + (sx + 0.5) / 16.0, y - 0.5 + (sy + 0.5) / 16.0);
          if (std::abs((p - centre).dot(axis)) <= l && std::abs((p - centre).dot(across)) <= r) {
            ++inside;
          }
        }
      }
      if (inside > 0) {
        out.points.emplace_back(x, y);
        out.weights.push_back(inside / 256.0);
      }
    }
  }
  return out;
}

TEST(BandShape, AnUprightBandIsItsRectangle) {
  const Eigen::Vector2d centre(20.3, 31.7);
  const Drawn d = DrawBand(centre, Eigen::Vector2d::UnitY(), 6.0, 3.0);
  const BandShape s = MeasureBandShape(d.points, d.weights, Eigen::Vector2d::Zero());
  EXPECT_NEAR(s.radius, 3.0, 0.1);
  EXPECT_NEAR(s.half_length, 6.0, 0.1);
  EXPECT_LT((s.center - centre).norm(), 0.05);
  EXPECT_GT(eval::BoxIou(s.Box(), {centre.x() - 3, centre.y() - 6, 6, 12}), 0.95);
}

TEST(BandShape, ATiltedBandsBoxBoundsItsRotatedRectangle) {
  const Eigen::Vector2d centre(40.2, 35.6), axis = Eigen::Vector2d(1.0, 2.0).normalized();
  const double l = 5.0, r = 2.5;
  const Drawn d = DrawBand(centre, axis, l, r);
  const BandShape s = MeasureBandShape(d.points, d.weights, Eigen::Vector2d::Zero());
  EXPECT_NEAR(std::abs(s.axis.dot(axis)), 1.0, 1e-3);
  EXPECT_NEAR(s.radius, r, 0.1);
  EXPECT_NEAR(s.half_length, l, 0.1);
  const double hx = l * axis.x() + r * axis.y(), hy = l * axis.y() + r * axis.x();
  EXPECT_GT(eval::BoxIou(s.Box(), {centre.x() - hx, centre.y() - hy, 2 * hx, 2 * hy}), 0.95);
}

TEST(BandShape, BlurIsTakenOffTheExtent) {
  // A Gaussian blur of variance b along x spreads each pixel's weight: the moments grow by b.
  const Eigen::Vector2d centre(30.0, 30.0);
  const Drawn sharp = DrawBand(centre, Eigen::Vector2d::UnitY(), 6.0, 3.0);
  Drawn blurred;
  const double b = 0.5;
  for (size_t i = 0; i < sharp.points.size(); ++i) {
    for (int dx = -3; dx <= 3; ++dx) {
      blurred.points.push_back(sharp.points[i] + Eigen::Vector2d(dx, 0));
      blurred.weights.push_back(sharp.weights[i] * std::exp(-dx * dx / (2 * b)));
    }
  }
  const double r = MeasureBandShape(sharp.points, sharp.weights, Eigen::Vector2d::Zero()).radius;
  const BandShape s = MeasureBandShape(blurred.points, blurred.weights, Eigen::Vector2d(b, 0));
  EXPECT_NEAR(s.radius, r, 0.02);
  EXPECT_NEAR(s.half_length, 6.0, 0.1);  // the blur was across the band only
  const BandShape raw = MeasureBandShape(blurred.points, blurred.weights, Eigen::Vector2d::Zero());
  EXPECT_GT(raw.radius, r + 0.2);
}

TEST(BandModel, KeepsTheBandsSizeInMetresAndItsDirectionEitherWayRound) {
  BandModel model;
  EXPECT_FALSE(model.known());
  BandShape s{.center = {10, 10}, .axis = {0.6, 0.8}, .half_length = 6, .radius = 2};
  model.Observe(s, 2.0);
  s.axis = {-0.6, -0.8};  // the same band, its axis found the other way round
  s.radius = 2.2;
  model.Observe(s, 2.0);
  ASSERT_TRUE(model.known());
  const BandShape at = model.At({50, 50}, 4.0);  // twice as far: half the size
  EXPECT_NEAR(at.axis.x(), 0.6, 1e-9);
  EXPECT_NEAR(at.axis.y(), 0.8, 1e-9);
  EXPECT_NEAR(at.half_length, 3.0, 1e-9);
  EXPECT_NEAR(at.radius, 1.05, 1e-9);  // the mean of 2 and 2.2, halved
  EXPECT_EQ(at.center, Eigen::Vector2d(50, 50));
}

TEST(BandModel, TheRadiusIsAveragedLongerThanTheLength) {
  // The radius is a constant of the band; the foreshortened length follows the branch's swing.
  BandModel model;
  BandShape s{.center = {0, 0}, .axis = {0, 1}, .half_length = 6, .radius = 2};
  for (int i = 0; i < 10; ++i) model.Observe(s, 1.0);
  s.half_length = 3;
  s.radius = 1;
  for (int i = 0; i < 5; ++i) model.Observe(s, 1.0);
  const BandShape at = model.At({0, 0}, 1.0);
  EXPECT_LT(at.half_length, 3.6);  // within a fifth of the change of 3 px after five frames
  EXPECT_GT(at.radius, 1.5);       // still nearer the ten frames before than the five after
}

}  // namespace
}  // namespace simtree::tracking::detail
