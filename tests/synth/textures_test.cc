#include "simtree/synth/detail/textures.h"
#include "simtree/synth/detail/camera_rig.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "simtree/core/error.h"
#include "simtree/synth/detail/rgbd_false_color.h"
#include "simtree/synth/detail/sensor_pose.h"

namespace simtree::synth {
namespace {

double Redness(const Rgb& c) { return c.x() - 0.5 * (c.y() + c.z()); }

TEST(Textures, NoiseIsSmoothBoundedDeterministicAndPeriodicWhenAsked) {
  for (int i = 0; i < 1000; ++i) {
    const double x = 0.37 * i, y = 0.11 * i;
    const float v = ValueNoise(x, y, 5);
    ASSERT_GE(v, 0.0f);
    ASSERT_LE(v, 1.0f);
    ASSERT_EQ(v, ValueNoise(x, y, 5));
    // Smooth: a small step changes it a little.
    ASSERT_LT(std::abs(ValueNoise(x + 1e-3, y, 5) - v), 0.01f);
    const float f = FractalNoise(x, y, 5, 3, 8);
    ASSERT_GE(f, 0.0f);
    ASSERT_LE(f, 1.0f);
    // Periodic in x with the period: no seam where a pattern wraps around a branch.
    ASSERT_NEAR(ValueNoise(x, y, 5, 8), ValueNoise(x + 8.0, y, 5, 8), 1e-5);
    ASSERT_NEAR(f, FractalNoise(x + 8.0, y, 5, 3, 8), 1e-5);
  }
  EXPECT_NE(ValueNoise(0.5, 0.5, 1), ValueNoise(0.5, 0.5, 2));
}

TEST(Textures, TapeIsRedBarkSkyAndGroundAreNot) {
  double bark_red = -1, tape_red = 1;
  for (int i = 0; i < 200; ++i) {
    const BarkPoint p{.arc_length_m = 0.013 * i,
                      .angle_rad = 0.05 * i - 3.0,
                      .radius_m = 0.002 + 0.0005 * i,
                      .branch = i % 7};
    const Rgb bark = BarkAlbedo(p, 3);
    ASSERT_TRUE((bark.array() >= 0.0f).all() && (bark.array() <= 1.0f).all());
    bark_red = std::max(bark_red, Redness(bark));
    tape_red = std::min(tape_red, Redness(TapeAlbedo(0.03 * i, 0.0002 * i - 0.02, 3)));
    EXPECT_LT(Redness(GroundAlbedo(0.1 * i, -0.07 * i, 3)), 0.15);
    EXPECT_LT(Redness(HedgeAlbedo(0.1 * i, 0.01 * i, 3)), 0.1);
  }
  EXPECT_LT(bark_red, 0.2);  // bark may be brown, never tape-red
  EXPECT_GT(tape_red, 0.5);
  // The sky is bluer overhead than at the horizon.
  const Rgb horizon = SkyColor({1, 0, 0});
  const Rgb zenith = SkyColor({0, 0, 1});
  EXPECT_GT(zenith.z() - zenith.x(), horizon.z() - horizon.x());
}

TEST(FalseColor, LabelsShowTapeRedAndBranchesApart) {
  LabelImage labels(2, 1);
  labels.at(0, 0).kind = SurfaceKind::kBranch;
  labels.at(0, 0).marker = 3;
  labels.at(1, 0).kind = SurfaceKind::kBranch;
  labels.at(1, 0).branch = 5;
  const RgbImage l = ColorizeLabels(labels);
  EXPECT_EQ(l.at(0, 0, 0), 255);
  EXPECT_EQ(l.at(0, 0, 1), 0);
  EXPECT_LT(l.at(1, 0, 0), 200);  // a branch is never pure red
}

TEST(SensorPose, OnlyRigidPosesPass) {
  const Eigen::Isometry3d pose = LookAt({2, 0, 1}, {0, 0, 1});
  EXPECT_NO_THROW(ValidateCameraPose(pose, "camera"));
  Eigen::Isometry3d mirrored = pose;
  mirrored.linear().col(0) *= -1.0;
  EXPECT_THROW(ValidateCameraPose(mirrored, "camera"), InputError);
}

}  // namespace
}  // namespace simtree::synth
