// The Brown-Conrady model and depth-to-colour registration against the math itself, with the real
// recording's factory calibration.

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "simtree/io/azure_kinect.h"
#include "test_util.h"

namespace simtree {
namespace {

AzureCalibration RealCalibration() {
  return ParseAzureCalibration(
      test::ReadText(test::SharedData("azure-kinect/pyk4a_calibration.json")), "calibration", 640,
      576, 1280, 720);
}

TEST(BrownConrady, DistortsAsTheSdkModelSays) {
  BrownConradyCamera c;
  c.k1 = 0.1;
  c.k4 = 0.05;
  c.p1 = 0.01;
  c.p2 = 0.02;
  const double x = 0.3, y = 0.2, r2 = x * x + y * y;
  const double d = (1 + 0.1 * r2) / (1 + 0.05 * r2);
  const Eigen::Vector2d got = c.Distort({x, y});
  EXPECT_NEAR(got.x(), x * d + (r2 + 2 * x * x) * 0.02 + 2 * x * y * 0.01, 1e-15);
  EXPECT_NEAR(got.y(), y * d + (r2 + 2 * y * y) * 0.01 + 2 * x * y * 0.02, 1e-15);
}

TEST(BrownConrady, ProjectAndUnprojectRoundTripOverBothCameras) {
  const AzureCalibration cal = RealCalibration();
  for (const BrownConradyCamera* camera : {&cal.depth, &cal.color}) {
    double worst = 0;
    for (int v = 0; v < camera->height; v += 37) {
      for (int u = 0; u < camera->width; u += 41) {
        const std::optional<Eigen::Vector2d> ray = camera->PixelRay(u, v);
        if (!ray) continue;  // outside the metric radius (depth corners)
        const std::optional<Eigen::Vector2d> back =
            camera->Project(Eigen::Vector3d(ray->x(), ray->y(), 1.0) * 2.5);
        ASSERT_TRUE(back.has_value()) << u << "," << v;
        worst = std::max(worst, (*back - Eigen::Vector2d(u, v)).norm());
      }
    }
    EXPECT_LT(worst, 1e-6);
  }
  // The depth camera's centre pixel is valid and near its optical axis.
  EXPECT_TRUE(cal.depth.PixelRay(cal.depth.cx, cal.depth.cy).has_value());
}

// The depth image the depth camera sees of the plane z = z_color in the colour camera, with
// +-noise_mm of deterministic noise as a real sensor has (neighbouring footprints then do not
// meet exactly).
DepthImage PlaneDepth(const AzureCalibration& cal, double z_color, int noise_mm = 0) {
  DepthImage depth(cal.depth.width, cal.depth.height, 0);
  const Eigen::RowVector3d normal = cal.depth_to_color.rotation.row(2);
  for (int v = 0; v < depth.height; ++v) {
    for (int u = 0; u < depth.width; ++u) {
      const std::optional<Eigen::Vector2d> ray = cal.depth.PixelRay(u, v);
      if (!ray) continue;
      const Eigen::Vector3d r(ray->x(), ray->y(), 1.0);
      const double t = (z_color - cal.depth_to_color.translation_m.z()) / normal.dot(r);
      const int noise =
          noise_mm > 0 ? static_cast<int>((u * 7919 + v * 104729) % (2 * noise_mm + 1)) - noise_mm
                       : 0;
      depth.at(u, v) = static_cast<uint16_t>(std::lround(t * 1000) + noise);
    }
  }
  return depth;
}

TEST(AzureRegistration, APlaneLandsAtItsDepthOnEveryColourPixelTheDepthCameraSees) {
  const AzureCalibration cal = RealCalibration();
  const AzureRegistration reg(cal);
  const DepthImage registered = reg.RegisterDepth(PlaneDepth(cal, 1.2, 4));
  const CameraIntrinsics& k = reg.color_pinhole();
  const RigidTransform color_to_depth = cal.depth_to_color.Inverse();
  int seen = 0, covered = 0;
  double worst_mm = 0;
  for (int v = 0; v < k.height; ++v) {
    for (int u = 0; u < k.width; ++u) {
      // Where the plane's point at this colour pixel falls in the depth image.
      const Eigen::Vector3d p = color_to_depth.Apply(k.Unproject(u, v, 1.2));
      const std::optional<Eigen::Vector2d> d = cal.depth.Project(p);
      if (!d || d->x() < 2 || d->y() < 2 || d->x() > cal.depth.width - 3 ||
          d->y() > cal.depth.height - 3 || !cal.depth.PixelRay(d->x(), d->y())) {
        continue;
      }
      ++seen;
      if (registered.at(u, v) == 0) continue;
      ++covered;
      worst_mm = std::max(worst_mm, std::abs(registered.at(u, v) - 1200.0));
    }
  }
  EXPECT_GT(seen, 300000);
  EXPECT_GT(static_cast<double>(covered) / seen, 0.999) << covered << " of " << seen;
  EXPECT_LE(worst_mm, 2.0 + 4.0);
}

TEST(AzureRegistration, ABlockLandsAtItsPixelInFrontOfTheBackground) {
  const AzureCalibration cal = RealCalibration();
  const AzureRegistration reg(cal);
  DepthImage depth(cal.depth.width, cal.depth.height, 2500);  // a wall 2.5 m away
  for (int v = 300; v < 306; ++v) {
    for (int u = 400; u < 406; ++u) depth.at(u, v) = 1000;  // a block in front of it
  }
  const DepthImage registered = reg.RegisterDepth(depth);
  // The block's centre (pixel corner 403, 303) moved into the colour camera by the math.
  const Eigen::Vector2d ray = *cal.depth.PixelRay(402.5, 302.5);
  const Eigen::Vector3d p = cal.depth_to_color.Apply(Eigen::Vector3d(ray.x(), ray.y(), 1) * 1.0);
  const Eigen::Vector2d expected = reg.color_pinhole().Project(p);
  double sum_u = 0, sum_v = 0;
  int n = 0;
  for (int v = 0; v < registered.height; ++v) {
    for (int u = 0; u < registered.width; ++u) {
      if (registered.at(u, v) == 0 || registered.at(u, v) > 1500) continue;
      EXPECT_NEAR(registered.at(u, v), p.z() * 1000, 3.0);
      sum_u += u;
      sum_v += v;
      ++n;
    }
  }
  ASSERT_GT(n, 20);
  EXPECT_NEAR(sum_u / n, expected.x(), 0.75);
  EXPECT_NEAR(sum_v / n, expected.y(), 0.75);
}

TEST(AzureRegistration, UndistortingAnImageTheLensBentGivesItBack) {
  const AzureCalibration cal = RealCalibration();
  const AzureRegistration reg(cal);
  const CameraIntrinsics& k = reg.color_pinhole();
  auto pattern = [](double u, double v) {
    return 128 + 100 * std::sin(u / 15.0) * std::cos(v / 20.0);
  };
  // What the distorted colour camera sees of the pattern drawn in the pinhole image.
  RgbImage distorted(cal.color.width, cal.color.height);
  for (int v = 0; v < distorted.height; ++v) {
    for (int u = 0; u < distorted.width; ++u) {
      const Eigen::Vector2d ray = *cal.color.PixelRay(u, v);
      const double value = pattern(k.fx * ray.x() + k.cx, k.fy * ray.y() + k.cy);
      for (int c = 0; c < 3; ++c) distorted.at(u, v, c) = static_cast<uint8_t>(std::lround(value));
    }
  }
  const RgbImage undistorted = reg.UndistortColor(distorted);
  double error = 0;
  int n = 0;
  for (int v = 60; v < k.height - 60; v += 3) {
    for (int u = 60; u < k.width - 60; u += 3) {
      error += std::abs(undistorted.at(u, v, 1) - pattern(u, v));
      ++n;
    }
  }
  EXPECT_LT(error / n, 1.5);
}

TEST(AzureRegistration, ColourInDepthSamplesWhereTheLensModelSendsEachPoint) {
  const AzureCalibration cal = RealCalibration();
  const AzureRegistration reg(cal);
  auto pattern = [](double u, double v) {
    return 128 + 100 * std::sin(u / 25.0) * std::cos(v / 30.0);
  };
  RgbImage color(cal.color.width, cal.color.height);
  for (int v = 0; v < color.height; ++v) {
    for (int u = 0; u < color.width; ++u) {
      for (int c = 0; c < 3; ++c)
        color.at(u, v, c) = static_cast<uint8_t>(std::lround(pattern(u, v)));
    }
  }
  const DepthImage depth = PlaneDepth(cal, 1.2);
  const RgbImage got = reg.ColorInDepth(color, depth);
  double error = 0;
  int n = 0;
  for (int v = 0; v < depth.height; v += 3) {
    for (int u = 0; u < depth.width; u += 3) {
      if (depth.at(u, v) == 0 || got.at(u, v, 0) == 0) continue;
      const Eigen::Vector2d ray = *cal.depth.PixelRay(u, v);
      const Eigen::Vector3d p =
          cal.depth_to_color.Apply(Eigen::Vector3d(ray.x(), ray.y(), 1) * (depth.at(u, v) * 0.001));
      const Eigen::Vector2d px = *cal.color.Project(p);
      error += std::abs(got.at(u, v, 0) - pattern(px.x(), px.y()));
      ++n;
    }
  }
  EXPECT_GT(n, 15000);
  EXPECT_LT(error / n, 1.0);
}

TEST(AzureRegistration, ColourInDepthLeavesPointsTheColourCameraCannotSeeBlack) {
  const AzureCalibration cal = RealCalibration();
  const AzureRegistration reg(cal);
  DepthImage depth(cal.depth.width, cal.depth.height, 2500);  // a wall
  for (int v = 200; v < 300; ++v) {
    for (int u = 250; u < 350; ++u) depth.at(u, v) = 600;  // a near box
  }
  const RgbImage color(cal.color.width, cal.color.height, 200);
  const RgbImage got = reg.ColorInDepth(color, depth);
  EXPECT_EQ(got.at(300, 250, 0), 200);  // the box
  EXPECT_EQ(got.at(100, 250, 0), 200);  // the wall far from it
  // The colour camera sits about 32 mm to the depth camera's -x: the wall just beside the box on
  // one side is in the box's shadow for it.
  int hidden = 0;
  for (int u = 350; u < 400; ++u) hidden += got.at(u, 250, 0) == 0;
  for (int u = 200; u < 250; ++u) hidden += got.at(u, 250, 0) == 0;
  EXPECT_GT(hidden, 10);
}

}  // namespace
}  // namespace simtree
