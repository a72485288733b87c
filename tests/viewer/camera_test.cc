// Cameras: a pixel's ray passes through the points that project to that pixel, a calibrated
// camera projects as its intrinsics do, and framing keeps a box in view.

#include "simtree/viewer/detail/camera.h"

#include <gtest/gtest.h>

#include "simtree/core/units.h"

namespace simtree::viewer {
namespace {

TEST(Camera, PixelRayAndProjectAgree) {
  OrbitCamera orbit;
  orbit.target = {0.5, -0.2, 1.0};
  orbit.yaw_rad = 0.7;
  orbit.pitch_rad = 0.3;
  orbit.distance_m = 4.0;
  const CameraView view = orbit.View(800, 600);
  EXPECT_TRUE(view.EyePosition().isApprox(orbit.Eye(), 1e-9));
  for (const Eigen::Vector2d& pixel :
       {Eigen::Vector2d(400, 300), Eigen::Vector2d(10.5, 590), Eigen::Vector2d(777, 20)}) {
    const Ray ray = view.PixelRay(pixel.x(), pixel.y());
    const auto back = view.Project(ray.origin + 3.0 * ray.direction);
    ASSERT_TRUE(back.has_value());
    EXPECT_NEAR(back->x(), pixel.x(), 1e-6);
    EXPECT_NEAR(back->y(), pixel.y(), 1e-6);
  }
  // The centre of the window looks at the target; points behind the eye do not project.
  const auto centre = view.Project(orbit.target);
  EXPECT_NEAR(centre->x(), 400, 1e-9);
  EXPECT_NEAR(centre->y(), 300, 1e-9);
  EXPECT_FALSE(view.Project(orbit.Eye() - 2.0 * view.Forward()).has_value());
}

TEST(Camera, PinholeViewProjectsLikeTheIntrinsics) {
  CameraIntrinsics k;
  k.width = 640;
  k.height = 576;
  k.fx = 504.2;
  k.fy = 503.9;
  k.cx = 321.7;
  k.cy = 330.1;
  Eigen::Isometry3d world_from_camera = Eigen::Isometry3d::Identity();
  world_from_camera.linear() =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(0.2, 1, 0.1).normalized()).toRotationMatrix();
  world_from_camera.translation() = Eigen::Vector3d(0.1, -2.5, 1.2);
  const CameraView view = PinholeView(k, world_from_camera);
  for (const Eigen::Vector3d& p_cam :
       {Eigen::Vector3d(0.1, -0.2, 2.5), Eigen::Vector3d(-0.7, 0.4, 3.0)}) {
    const Eigen::Vector2d expected = k.Project(p_cam);
    const auto got = view.Project(world_from_camera * p_cam);
    ASSERT_TRUE(got.has_value());
    // Window coordinates put pixel centres at +0.5.
    EXPECT_NEAR(got->x(), expected.x() + 0.5, 1e-6);
    EXPECT_NEAR(got->y(), expected.y() + 0.5, 1e-6);
  }
}

TEST(Camera, FrameKeepsTheBoxInView) {
  OrbitCamera orbit;
  const Eigen::Vector3d lo(-1, -0.5, 0), hi(1.5, 0.5, 4);
  orbit.Frame(lo, hi, 16.0 / 9.0);
  const CameraView view = orbit.View(1600, 900);
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(),
                            (corner & 4) ? hi.z() : lo.z());
    const auto pixel = view.Project(p);
    ASSERT_TRUE(pixel.has_value());
    EXPECT_GE(pixel->x(), 0);
    EXPECT_LE(pixel->x(), 1600);
    EXPECT_GE(pixel->y(), 0);
    EXPECT_LE(pixel->y(), 900);
  }
  const double before = orbit.distance_m;
  orbit.Zoom(0.5);
  EXPECT_DOUBLE_EQ(orbit.distance_m, before / 2);
  orbit.Zoom(-1);  // ignored
  EXPECT_DOUBLE_EQ(orbit.distance_m, before / 2);
  orbit.Orbit(0, 10);
  EXPECT_LT(orbit.pitch_rad, kPi / 2);
}

}  // namespace
}  // namespace simtree::viewer
