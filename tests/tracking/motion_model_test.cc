#include "simtree/tracking/detail/motion_model.h"

#include <cmath>

#include <gtest/gtest.h>

namespace simtree::tracking::detail {
namespace {

TEST(MotionModel, ConstantVelocityLearnsTheVelocityAndPredictsAhead) {
  MotionModelParams params;
  const double dt = 1.0 / 30.0;
  const Eigen::Vector3d v(0.3, -0.1, 0.05);
  MarkerMotionModel model(params, Eigen::Vector3d(0, 0, 2));
  for (int k = 1; k <= 30; ++k) {
    model.Predict(dt);
    model.Update(Eigen::Vector3d(0, 0, 2) + v * k * dt);
  }
  EXPECT_LT((model.velocity() - v).norm(), 0.02);
  model.Predict(dt);
  EXPECT_LT((model.position() - (Eigen::Vector3d(0, 0, 2) + v * 31 * dt)).norm(), 0.002);
}

TEST(MotionModel, ScaleVelocityShrinksOnlyTheVelocity) {
  MarkerMotionModel model(MotionModelParams{}, Eigen::Vector3d(0, 0, 2));
  for (int k = 1; k <= 10; ++k) {
    model.Predict(1.0 / 30.0);
    model.Update(Eigen::Vector3d(0.01 * k, 0, 2));
  }
  const Eigen::Vector3d p = model.position(), v = model.velocity();
  model.ScaleVelocity(0.5);
  EXPECT_LT((model.velocity() - 0.5 * v).norm(), 1e-12);
  EXPECT_LT((model.position() - p).norm(), 1e-12);
}

TEST(MotionModel, UncertaintyGrowsWhileCoasting) {
  MarkerMotionModel model(MotionModelParams{}, Eigen::Vector3d(0, 0, 2));
  const double before = model.position_sigma().norm();
  for (int k = 0; k < 5; ++k) model.Predict(1.0 / 30.0);
  EXPECT_GT(model.position_sigma().norm(), before);
}

TEST(MotionModel, OscillatorFollowsASwingAboutRest) {
  MotionModelParams params;
  params.kind = MotionModelKind::kDampedOscillator;
  params.oscillator_frequency_hz = 1.0;
  const Eigen::Vector3d rest(0.1, 0.2, 2.0);
  MarkerMotionModel model(params, rest);
  const double dt = 1.0 / 30.0;
  double worst = 0.0;
  for (int k = 1; k <= 90; ++k) {
    const double t = k * dt;
    const Eigen::Vector3d truth = rest + Eigen::Vector3d(0.05 * std::sin(2 * M_PI * t), 0, 0);
    model.Predict(dt);
    if (k > 30) worst = std::max(worst, (model.position() - truth).norm());
    model.Update(truth);
  }
  EXPECT_LT(worst, 0.01);
  EXPECT_EQ(model.rest(), rest);
}

}  // namespace
}  // namespace simtree::tracking::detail
