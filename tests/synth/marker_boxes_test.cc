#include "simtree/synth/detail/marker_boxes.h"
#include "simtree/synth/detail/camera_rig.h"

#include <gtest/gtest.h>

#include <cmath>

#include "simtree/core/error.h"
#include "simtree/io/image_io.h"
#include "simtree/synth/detail/rgbd_false_color.h"
#include "simtree/synth/detail/rgbd_renderer.h"
#include "simtree/synth/detail/sensor_pose.h"
#include "synth/sensor_fixtures.h"

namespace simtree::synth {
namespace {

// Whether pixel centre (x, y) lies in a box [x, y, w, h].
bool Inside(const std::array<double, 4>& box, int x, int y) {
  return x >= box[0] && x <= box[0] + box[2] && y >= box[1] && y <= box[1] + box[3];
}

// A vertical cylinder with one tape marker at height 1 m, seen from x = 2 m.
struct TapedCylinder {
  Tree tree;
  TapedCylinder() : tree(test::VerticalCylinder(0, 0, 2.0, 0.03)) {
    tree.markers.push_back({0, "M0", 0, 1.0, -1, {0, 0, 1.0}});
  }
};

TEST(MarkerBoxes, AnUnoccludedBandIsWhollyVisibleAndItsBoxIsItsProjection) {
  const TapedCylinder t;
  const SensorScene scene(t.tree, test::BareScene());
  const SensorModel sensor = SensorModel::AzureKinectNfov();
  const Eigen::Isometry3d camera = LookAt({2.0, 0, 1.0}, {0, 0, 1.0});
  const RenderResult r = RenderRgbd(scene, sensor, camera, {.seed = 1});
  ASSERT_EQ(r.markers.size(), 1u);
  const MarkerObservation& m = r.markers[0];
  EXPECT_EQ(m.box.id, 0);
  EXPECT_TRUE(m.box.visible);
  EXPECT_NEAR(m.box.visible_fraction, 1.0, 0.02);
  EXPECT_EQ(m.box.visible_pixels, m.band_pixels);
  EXPECT_NEAR(m.center_camera.z(), 2.0, 1e-9);
  EXPECT_NEAR(m.center_camera.x(), 0.0, 1e-9);
  // Box: about 2 r f / d wide (a little more: the near rim is nearer) and w f / d high.
  const double f = sensor.FocalLengthPx();
  EXPECT_NEAR(m.box.box[2], 2 * 0.03 * f / (2.0 - 0.03), 1.0);
  EXPECT_NEAR(m.box.box[3], 0.04 * f / (2.0 - 0.03), 1.0);
  EXPECT_NEAR(m.box.box[0] + 0.5 * m.box.box[2], 319.5, 0.5);
  EXPECT_NEAR(m.box.box[1] + 0.5 * m.box.box[3], 287.5, 0.5);
}

TEST(MarkerBoxes, AnOccluderInFrontLowersTheVisibleFraction) {
  const TapedCylinder t;
  const SensorModel sensor = SensorModel::AzureKinectNfov();
  const Eigen::Isometry3d camera = LookAt({2.0, 0, 1.0}, {0, 0, 1.0});
  auto fraction = [&](double box_y) {
    SceneOptions o = test::BareScene();
    // A thin board at x = 1 covering y > box_y.
    o.boxes.push_back({.center = {1.0, box_y + 0.5, 1.0},
                       .half_extent = {0.01, 0.5, 0.5},
                       .kind = SurfaceKind::kOccluder});
    const SensorScene scene(t.tree, o);
    const RenderResult r = RenderRgbd(scene, sensor, camera, {.seed = 1});
    return r.markers[0].box;
  };
  const MarkerBox2d open = fraction(0.5);  // the board is aside
  const MarkerBox2d half = fraction(0.0);  // covers half the band (the ray to it crosses y=0)
  const MarkerBox2d covered = fraction(-0.2);
  EXPECT_NEAR(open.visible_fraction, 1.0, 0.02);
  EXPECT_NEAR(half.visible_fraction, 0.5, 0.1);
  EXPECT_EQ(covered.visible_fraction, 0.0);
  EXPECT_EQ(covered.visible_pixels, 0);
  EXPECT_FALSE(covered.visible);
  EXPECT_TRUE(half.visible);
  EXPECT_EQ(open.box, covered.box);  // the box is the band's, occluded or not
}

TEST(MarkerBoxes, BoxesContainEveryPixelLabelledWithTheirMarkerOnTree02) {
  const Tree tree = test::Tree02WithMarkers();
  ASSERT_GE(tree.markers.size(), 8u);
  const SensorScene scene(tree, DefaultSceneOptions(tree, 3, true));
  const SensorModel sensor = SensorModel::AzureKinectNfov();
  int seen = 0, partly_hidden = 0;
  for (int view = 0; view < 6; ++view) {
    const double a = view * 1.047;
    const Eigen::Isometry3d camera =
        LookAt({2.6 * std::cos(a), 2.6 * std::sin(a), 1.2 + 0.2 * view}, {0, 0, 2.0});
    const RenderResult r = RenderRgbd(scene, sensor, camera, {.seed = 2, .frame = view});
    if (view == 0) {
      const auto dir = test::TempDir();
      RgbImage boxes = r.image.color;
      for (const MarkerObservation& m : r.markers) {  // draw the boxes to look at them
        if (m.box.box[2] <= 0) continue;
        for (int x = static_cast<int>(m.box.box[0]); x <= m.box.box[0] + m.box.box[2]; ++x) {
          for (int y :
               {static_cast<int>(m.box.box[1]), static_cast<int>(m.box.box[1] + m.box.box[3])}) {
            if (x >= 0 && x < boxes.width && y >= 0 && y < boxes.height) {
              boxes.at(x, y, 0) = 255;
              boxes.at(x, y, 1) = boxes.at(x, y, 2) = 255 * m.box.visible;
            }
          }
        }
      }
      WritePng(boxes, dir / "tree02_marker_boxes.png");
    }
    ASSERT_EQ(r.markers.size(), tree.markers.size());
    for (size_t k = 0; k < r.markers.size(); ++k) {
      const MarkerObservation& m = r.markers[k];
      EXPECT_EQ(m.box.id, tree.markers[k].id);
      int labelled = 0;
      for (int y = 0; y < r.labels.height; ++y) {
        for (int x = 0; x < r.labels.width; ++x) {
          if (r.labels.at(x, y).marker != m.box.id) continue;
          ++labelled;
          ASSERT_TRUE(Inside(m.box.box, x, y))
              << "marker " << m.box.id << " pixel " << x << " " << y << " view " << view;
        }
      }
      EXPECT_EQ(labelled, m.box.visible_pixels);
      EXPECT_LE(m.box.visible_pixels, m.band_pixels + 2);
      EXPECT_GE(m.box.visible_fraction, 0.0);
      EXPECT_LE(m.box.visible_fraction, 1.0);
      seen += m.box.visible;
      partly_hidden += m.box.visible_pixels > 0 && m.box.visible_fraction < 0.9;
      // The centre projects inside the box when it is in front of the camera and in the image.
      const Eigen::Vector2d c = r.image.intrinsics.Project(m.center_camera);
      if (m.center_camera.z() > 0 && r.image.intrinsics.Contains(c.x(), c.y())) {
        EXPECT_TRUE(Inside(m.box.box, static_cast<int>(std::round(c.x())),
                           static_cast<int>(std::round(c.y()))) ||
                    m.box.box[2] < 2)
            << m.box.id;
      }
    }
  }
  EXPECT_GT(seen, 20);          // most markers in most views
  EXPECT_GT(partly_hidden, 3);  // and some hidden behind branches
}

TEST(MarkerBoxes, AMarkerBehindTheCameraHasNoBox) {
  const TapedCylinder t;
  const SensorScene scene(t.tree, test::BareScene());
  const Eigen::Isometry3d camera = LookAt({2.0, 0, 1.0}, {4.0, 0, 1.0});  // looking away
  const RenderResult r = RenderRgbd(scene, SensorModel::AzureKinectNfov(), camera);
  const MarkerBox2d& box = r.markers[0].box;
  EXPECT_EQ(box.box, (std::array<double, 4>{0, 0, 0, 0}));
  EXPECT_FALSE(box.visible);
  EXPECT_EQ(box.visible_fraction, 0.0);
  EXPECT_LT(r.markers[0].center_camera.z(), 0.0);
}

TEST(MarkerBoxes, RefusesLabelsOfAnotherSize) {
  const TapedCylinder t;
  const SensorScene scene(t.tree, test::BareScene());
  const CameraIntrinsics k = SensorModel::AzureKinectNfov().Intrinsics();
  const Eigen::Isometry3d camera = LookAt({2.0, 0, 1.0}, {0, 0, 1.0});
  EXPECT_THROW(ComputeMarkerBoxes(scene, k, camera, LabelImage(10, 10)), InputError);
  CameraIntrinsics zero = k;
  zero.width = 0;
  EXPECT_THROW(ComputeMarkerBoxes(scene, zero, camera, LabelImage()), InputError);
}

}  // namespace
}  // namespace simtree::synth
