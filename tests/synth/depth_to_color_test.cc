// Depth registered into the Azure Kinect's colour camera (depth_to_color.h, through pull_rig.h):
// a box's front face and the ground seen by the depth camera and registered into the 1280 x 720
// colour camera against their analytic depth in the colour camera.

#include "simtree/synth/detail/depth_to_color.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "simtree/core/error.h"
#include "simtree/synth/detail/camera_rig.h"
#include "simtree/synth/detail/pull_rig.h"
#include "synth/sensor_fixtures.h"

namespace simtree::synth {
namespace {

// The box: its front face is the plane y = kFaceY, |x| <= 0.5, 0 <= z <= 1 (the camera sees no
// other face of it); the ground is z = 0.
constexpr double kFaceY = -0.1;

SceneOptions BoxOnGround() {
  SceneOptions o = test::BareScene();
  o.ground = true;
  o.boxes.push_back(SceneBox{.center = {0.0, 0.0, 0.5}, .half_extent = {0.5, 0.1, 0.5}});
  return o;
}

// The tree is a stick behind the camera: only the box and the ground are in view.
Tree StickBehindTheCamera() { return test::VerticalCylinder(0.0, -6.0, 1.0, 0.02); }

// Analytic depth (colour camera z, metres) of the box face or the ground at colour pixel (u, v);
// 0 for the sky.
double AnalyticDepth(const Eigen::Isometry3d& camera, const CameraIntrinsics& k, double u,
                     double v) {
  const Eigen::Vector3d d =
      camera.linear() * Eigen::Vector3d((u - k.cx) / k.fx, (v - k.cy) / k.fy, 1.0);
  const Eigen::Vector3d o = camera.translation();
  if (std::abs(d.y()) > 1e-12) {
    const double t = (kFaceY - o.y()) / d.y();
    const Eigen::Vector3d p = o + t * d;
    if (t > 0 && std::abs(p.x()) <= 0.5 && p.z() >= 0.0 && p.z() <= 1.0) return t;
  }
  if (d.z() < -1e-12) return -o.z() / d.z();  // the ground (d has camera z 1: t is the depth)
  return 0.0;
}

struct Truth {
  std::vector<double> z;      // per colour pixel, metres (0: sky)
  std::vector<double> slope;  // largest change to a 4-neighbour, metres
  std::vector<bool> face;     // on the box's front face
};

Truth AnalyticTruth(const PullRig& rig) {
  const CameraIntrinsics k = rig.Intrinsics();
  const Eigen::Isometry3d camera = rig.WorldFromImage();
  Truth t;
  t.z.resize(static_cast<size_t>(k.width) * k.height);
  t.slope.assign(t.z.size(), 0.0);
  t.face.assign(t.z.size(), false);
  for (int v = 0; v < k.height; ++v) {
    for (int u = 0; u < k.width; ++u) {
      const size_t i = static_cast<size_t>(v) * k.width + u;
      t.z[i] = AnalyticDepth(camera, k, u, v);
      const Eigen::Vector3d p =
          camera * k.Unproject(u, v, t.z[i] > 0 ? t.z[i] : 1.0);  // world point of the pixel
      t.face[i] = t.z[i] > 0 && std::abs(p.y() - kFaceY) < 1e-6;
      for (const auto& [du, dv] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, {0, -1}}) {
        t.slope[i] =
            std::max(t.slope[i], std::abs(AnalyticDepth(camera, k, u + du, v + dv) - t.z[i]));
      }
    }
  }
  return t;
}

PullRig ColorRig(const SensorModel& sensor) {
  PullRig rig;
  rig.world_from_depth = LookAt({0.2, -1.6, 0.6}, {0.0, 0.0, 0.5});
  rig.depth_sensor = sensor;
  rig.color = AzureColorCamera::ForSize(1280, 720);
  return rig;
}

// Whether the truth changes by more than 5 cm (an edge, or the sky) within `radius` px.
bool NearAnEdge(const Truth& t, const CameraIntrinsics& k, int u, int v, int radius) {
  const double z = t.z[static_cast<size_t>(v) * k.width + u];
  for (int y = std::max(0, v - radius); y <= std::min(k.height - 1, v + radius); ++y) {
    for (int x = std::max(0, u - radius); x <= std::min(k.width - 1, u + radius); ++x) {
      const double zn = t.z[static_cast<size_t>(y) * k.width + x];
      if (zn == 0.0 || std::abs(zn - z) > 0.05) return true;
    }
  }
  return false;
}

// Whether the depth camera could measure a colour-camera point: inside its image (2 px in) and
// its range along the ray (0.1 m in).
bool SeenByTheDepthCamera(const PullRig& rig, const Eigen::Vector3d& point_color) {
  const Eigen::Vector3d p = rig.color->color_from_depth.inverse() * point_color;
  const CameraIntrinsics kd = rig.depth_sensor.Intrinsics();
  const Eigen::Vector2d uv = kd.Project(p);
  return uv.x() > 2 && uv.y() > 2 && uv.x() < kd.width - 3 && uv.y() < kd.height - 3 &&
         p.norm() < rig.depth_sensor.max_range_m - 0.1;
}

// Tolerance of an exact (Ideal) registration at a pixel: two roundings to the millimetre, and the
// depth of a neighbour up to 1.6 colour pixels away (a depth pixel spans 1.47 of them).
double IdealTolerance(const Truth& t, size_t i) { return 0.0011 + 1.6 * t.slope[i]; }

TEST(DepthToColor, ExactDepthRegistersToTheAnalyticDepthWithoutGapsOrInventedEdges) {
  const PullRig rig = ColorRig(SensorModel::Ideal());
  const SensorScene scene(StickBehindTheCamera(), BoxOnGround());
  const RenderResult r = RenderPullRig(scene, rig, {.shadows = false, .marker_boxes = false});
  const CameraIntrinsics k = rig.Intrinsics();
  ASSERT_EQ(r.image.depth.width, 1280);
  ASSERT_EQ(r.image.depth.height, 720);
  EXPECT_EQ(r.image.intrinsics, k);
  const Truth truth = AnalyticTruth(rig);

  int face = 0, face_filled = 0, ground = 0, ground_filled = 0, invented = 0;
  double worst_interior = 0.0;
  for (int v = 0; v < k.height; ++v) {
    for (int u = 0; u < k.width; ++u) {
      const size_t i = static_cast<size_t>(v) * k.width + u;
      const double measured = 0.001 * r.image.depth.pixels[i];
      // Anywhere: a registered depth is the truth of this pixel or of one beside it.
      if (measured > 0) {
        bool matches = false;
        for (int y = std::max(0, v - 1); y <= std::min(k.height - 1, v + 1); ++y) {
          for (int x = std::max(0, u - 1); x <= std::min(k.width - 1, u + 1); ++x) {
            const size_t j = static_cast<size_t>(y) * k.width + x;
            matches |=
                truth.z[j] > 0 && std::abs(measured - truth.z[j]) <= IdealTolerance(truth, j);
          }
        }
        invented += !matches;
      }
      // Away from edges (and from the parallax strip beside the box: the depth camera is 32 mm to
      // the side), inside the depth camera's range: every pixel filled, with its own depth.
      if (truth.z[i] == 0 || !SeenByTheDepthCamera(rig, k.Unproject(u, v, truth.z[i])) ||
          NearAnEdge(truth, k, u, v, 10)) {
        continue;
      }
      const bool filled = measured > 0;
      (truth.face[i] ? face : ground) += 1;
      (truth.face[i] ? face_filled : ground_filled) += filled;
      if (filled) {
        worst_interior =
            std::max(worst_interior, std::abs(measured - truth.z[i]) - IdealTolerance(truth, i));
      }
    }
  }
  EXPECT_GT(face, 100000);
  EXPECT_GT(ground, 20000);
  EXPECT_EQ(face_filled, face);
  EXPECT_EQ(ground_filled, ground);
  EXPECT_LE(worst_interior, 0.0);
  EXPECT_EQ(invented, 0);
}

TEST(DepthToColor, MeasuredDepthOfAFaceMatchesTheAnalyticDepthWithinTheSensorNoise) {
  const SensorModel sensor = SensorModel::AzureKinectNfov();
  const PullRig rig = ColorRig(sensor);
  const SensorScene scene(StickBehindTheCamera(), BoxOnGround());
  const RenderResult r =
      RenderPullRig(scene, rig, {.seed = 5, .shadows = false, .marker_boxes = false});
  const CameraIntrinsics k = rig.Intrinsics();
  const Truth truth = AnalyticTruth(rig);
  std::vector<double> errors;
  double mean_z = 0.0;
  for (int v = 0; v < k.height; ++v) {
    for (int u = 0; u < k.width; ++u) {
      const size_t i = static_cast<size_t>(v) * k.width + u;
      if (!truth.face[i] || NearAnEdge(truth, k, u, v, 10) || r.image.depth.pixels[i] == 0) {
        continue;
      }
      errors.push_back(0.001 * r.image.depth.pixels[i] - truth.z[i]);
      mean_z += truth.z[i];
    }
  }
  ASSERT_GT(errors.size(), 100000u);
  mean_z /= static_cast<double>(errors.size());
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2];
  // Robust spread (outliers are part of the model): half the central 68%.
  const double spread = 0.5 * (errors[static_cast<size_t>(0.84 * errors.size())] -
                               errors[static_cast<size_t>(0.16 * errors.size())]);
  // The systematic error: offset and scale, plus the fixed pattern's +- 2 mm.
  const double bias = sensor.bias_offset_m + sensor.bias_scale * mean_z;
  EXPECT_NEAR(median, bias, sensor.bias_pattern_m + 0.001) << "mean depth " << mean_z;
  // The random error facing the camera (within 20 degrees), the fixed pattern's spread over the
  // face and two roundings to the millimetre.
  const double noise = sensor.DepthNoiseStd(mean_z, std::cos(20.0 * std::numbers::pi / 180.0));
  EXPECT_GT(spread, 0.8 * sensor.DepthNoiseStd(mean_z, 1.0));
  EXPECT_LT(spread, std::hypot(noise, sensor.bias_pattern_m, 0.0005) + 0.0005);
}

TEST(DepthToColor, RefusesADepthImageOfAnotherSize) {
  const PullRig rig = ColorRig(SensorModel::Ideal());
  const CameraIntrinsics kd = rig.depth_sensor.Intrinsics();
  EXPECT_THROW(RegisterDepthToColor(DepthImage(kd.width - 1, kd.height), kd, rig.Intrinsics(),
                                    rig.color->color_from_depth),
               InputError);
}

}  // namespace
}  // namespace simtree::synth
