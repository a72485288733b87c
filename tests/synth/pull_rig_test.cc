// The pull test's camera (pull_rig.h) and the Azure Kinect's colour camera (azure_color_camera.h):
// without a colour camera the stream renders as ever; with one, its intrinsics, pose and marker
// boxes are the colour camera's.

#include "simtree/synth/detail/pull_rig.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "simtree/core/error.h"
#include "simtree/synth/detail/camera_rig.h"
#include "synth/sensor_fixtures.h"

namespace simtree::synth {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

TEST(AzureColorCamera, ColourModesHaveTheSpecFieldOfView) {
  const AzureColorCamera hd = AzureColorCamera::ForSize(1280, 720);
  const CameraIntrinsics k = hd.Intrinsics();
  EXPECT_EQ(k.width, 1280);
  EXPECT_EQ(k.height, 720);
  EXPECT_EQ(k.fx, k.fy);
  // The geometric mean of 640 / tan(45 deg) and 360 / tan(29.5 deg).
  EXPECT_NEAR(k.fx, std::sqrt(640.0 * 360.0 / std::tan(29.5 * kDegree)), 1e-9);
  EXPECT_NEAR(k.HorizontalFov() / kDegree, 90.0, 0.5);
  EXPECT_NEAR(k.VerticalFov() / kDegree, 59.0, 0.5);
  EXPECT_NEAR(AzureColorCamera::ForSize(2048, 1536).Intrinsics().VerticalFov() / kDegree, 74.3,
              0.7);
  // The colour camera 32 mm beside the depth camera; the depth camera's axis about 5 degrees
  // below the colour camera's.
  EXPECT_NEAR(hd.color_from_depth.translation().norm(), 0.0325, 0.001);
  const Eigen::Vector3d depth_axis = hd.color_from_depth.linear() * Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(std::atan2(depth_axis.y(), depth_axis.z()) / kDegree, 4.94, 0.01);
}

TEST(AzureColorCamera, OtherSizesAreRefusedNamingTheSize) {
  for (const auto& [w, h] : {std::pair{1280, 721}, std::pair{640, 480}, std::pair{0, 0}}) {
    try {
      AzureColorCamera::ForSize(w, h, "--color-size");
      ADD_FAILURE() << w << "x" << h << " accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("--color-size"), std::string::npos) << what;
      EXPECT_NE(what.find(std::to_string(w) + "x" + std::to_string(h)), std::string::npos) << what;
      EXPECT_NE(what.find("1280x720"), std::string::npos) << what;
    }
  }
}

PullRig Tree02Rig(const Tree& tree, bool color) {
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  PullRig rig;
  rig.world_from_depth = LookAt({2.6, 0.9, 1.3}, {0.0, 0.0, 0.5 * (lo.z() + hi.z())});
  rig.depth_sensor = SensorModel::AzureKinectNfov();
  if (color) rig.color = AzureColorCamera::ForSize(1280, 720);
  return rig;
}

TEST(PullRig, WithoutAColourCameraItIsTheDepthCamerasRender) {
  const Tree tree = test::Tree02WithMarkers();
  const SensorScene scene(tree, DefaultSceneOptions(tree, 3));
  const PullRig rig = Tree02Rig(tree, false);
  const RenderOptions options{.seed = 9, .frame = 4};
  const RenderResult a = RenderPullRig(scene, rig, options);
  const RenderResult b = RenderRgbd(scene, rig.depth_sensor, rig.world_from_depth, options);
  EXPECT_EQ(a.image.color, b.image.color);
  EXPECT_EQ(a.image.depth, b.image.depth);
  EXPECT_EQ(a.image.intrinsics, rig.depth_sensor.Intrinsics());
  EXPECT_TRUE(rig.WorldFromImage().isApprox(rig.world_from_depth));
}

TEST(PullRig, MarkerBoxesAreTheColourCamerasAndHoldTheirTape) {
  const Tree tree = test::Tree02WithMarkers();
  const SensorScene scene(tree, DefaultSceneOptions(tree, 3));
  const PullRig depth_rig = Tree02Rig(tree, false);
  const PullRig rig = Tree02Rig(tree, true);
  const CameraIntrinsics k = rig.Intrinsics();
  const RenderResult r = RenderPullRig(scene, rig, {.seed = 9, .shadows = false});
  const RenderResult d = RenderPullRig(scene, depth_rig, {.seed = 9, .shadows = false});
  ASSERT_EQ(r.labels.width, 1280);
  ASSERT_EQ(r.markers.size(), tree.markers.size());
  const Eigen::Isometry3d color_from_world = rig.WorldFromImage().inverse();
  std::vector<double> width_ratios;
  int visible = 0;
  for (size_t m = 0; m < tree.markers.size(); ++m) {
    const MarkerBox2d& box = r.markers[m].box;
    // The centre is the marker's, in the colour camera's frame.
    EXPECT_LT((r.markers[m].center_camera - color_from_world * tree.markers[m].position).norm(),
              1e-9);
    if (!box.visible) continue;
    ++visible;
    const Eigen::Vector2d uv = k.Project(r.markers[m].center_camera);
    EXPECT_GE(uv.x(), box.box[0]);
    EXPECT_LE(uv.x(), box.box[0] + box.box[2]);
    EXPECT_GE(uv.y(), box.box[1]);
    EXPECT_LE(uv.y(), box.box[1] + box.box[3]);
    // Every pixel the colour camera gives to the tape lies in its box.
    int outside = 0, tape = 0;
    for (int y = 0; y < k.height; ++y) {
      for (int x = 0; x < k.width; ++x) {
        if (r.labels.at(x, y).marker != tree.markers[m].id) continue;
        ++tape;
        outside += x < box.box[0] || x > box.box[0] + box.box[2] || y < box.box[1] ||
                   y > box.box[1] + box.box[3];
      }
    }
    EXPECT_EQ(tape, box.visible_pixels);
    EXPECT_EQ(outside, 0) << "marker " << m;
    if (d.markers[m].box.visible) width_ratios.push_back(box.box[2] / d.markers[m].box.box[2]);
  }
  EXPECT_GE(visible, 3);
  // The tape spans as many more pixels as the focal lengths say (434 px -> 638 px).
  ASSERT_FALSE(width_ratios.empty());
  std::sort(width_ratios.begin(), width_ratios.end());
  EXPECT_NEAR(width_ratios[width_ratios.size() / 2], k.fx / depth_rig.Intrinsics().fx, 0.15);
}

}  // namespace
}  // namespace simtree::synth
