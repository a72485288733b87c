#include "simtree/synth/detail/rgbd_renderer.h"
#include "simtree/synth/detail/camera_rig.h"

#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "simtree/core/error.h"
#include "simtree/io/depth_colormap.h"
#include "simtree/io/image_io.h"
#include "simtree/synth/detail/rgbd_false_color.h"
#include "simtree/synth/detail/sensor_pose.h"
#include "synth/sensor_fixtures.h"

namespace simtree::synth {
namespace {

const Eigen::Vector3d kNaN3(std::numeric_limits<double>::quiet_NaN(), 0, 0);

// The depth (camera z) at which the ray of pixel (x, y) meets the vertical cylinder of `radius`
// about the world z axis; 0 when it misses.
double CylinderDepth(const Eigen::Isometry3d& camera, const CameraIntrinsics& k, int x, int y,
                     double radius) {
  const Eigen::Vector3d d =
      camera.linear() * Eigen::Vector3d((x - k.cx) / k.fx, (y - k.cy) / k.fy, 1);
  const Eigen::Vector3d o = camera.translation();
  const double a = d.x() * d.x() + d.y() * d.y();
  const double b = 2 * (o.x() * d.x() + o.y() * d.y());
  const double c = o.x() * o.x() + o.y() * o.y() - radius * radius;
  const double disc = b * b - 4 * a * c;
  if (disc < 0) return 0.0;
  return (-b - std::sqrt(disc)) / (2 * a);  // t along d, whose camera z is 1: the depth
}

// Whether a 4-neighbour's true depth differs by more than `jump` (or it sees nothing).
bool NextToADiscontinuity(const LabelImage& labels, int x, int y, double jump) {
  const double z = labels.at(x, y).depth_m;
  const int dx[] = {1, -1, 0, 0};
  const int dy[] = {0, 0, 1, -1};
  for (int n = 0; n < 4; ++n) {
    const int nx = x + dx[n], ny = y + dy[n];
    if (nx < 0 || ny < 0 || nx >= labels.width || ny >= labels.height) continue;
    const double zn = labels.at(nx, ny).depth_m;
    if (zn == 0.0 || std::abs(zn - z) > jump) return true;
  }
  return false;
}

// A camera `distance` from the tree's trunk axis at `height`, aimed at the crown's middle, at
// azimuth `azimuth_rad` around the trunk.
Eigen::Isometry3d CameraAroundTree(const Tree& tree, double distance, double height,
                                   double azimuth_rad) {
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  const Eigen::Vector3d base = tree.trunk().base().position;
  const Eigen::Vector3d target(base.x(), base.y(), 0.5 * (lo.z() + hi.z()));
  const Eigen::Vector3d eye = base + Eigen::Vector3d(distance * std::cos(azimuth_rad),
                                                     distance * std::sin(azimuth_rad), height);
  return LookAt(eye, target);
}

TEST(RgbdRenderer, Tree02LooksLikeATreeOnGrassUnderASky) {
  const Tree tree = test::Tree02WithMarkers();
  ASSERT_GE(tree.markers.size(), 5u);
  SensorScene scene(tree, DefaultSceneOptions(tree, 7));
  const SensorModel sensor = SensorModel::AzureKinectNfov();
  const auto dir = test::TempDir();
  for (int view = 0; view < 3; ++view) {
    const Eigen::Isometry3d camera = CameraAroundTree(tree, 3.0, 1.4, 2.1 * view);
    if (view == 2) {  // a pull: a rope from a first-level branch to a stake on the ground
      const int branch = tree.markers[1].branch;
      scene.SetRope(RopeSegment{.branch = branch,
                                .arc_length = 0.8 * tree.branches[branch].Length(),
                                .anchor = camera.translation() + Eigen::Vector3d(0.6, 1.2, -1.4)});
    }
    const RenderResult r = RenderRgbd(scene, sensor, camera, {.seed = 7, .frame = view});
    const std::string name = "tree02_view" + std::to_string(view);
    WritePng(r.image.color, dir / (name + "_color.png"));
    WritePng(ColorizeDepth(r.image.depth), dir / (name + "_depth.png"));
    WritePng(ColorizeLabels(r.labels), dir / (name + "_labels.png"));
    // The tree covers a good part of the frame, and so do ground and sky.
    size_t branch = 0, ground = 0, sky = 0, tape = 0;
    for (const PixelLabel& l : r.labels.pixels) {
      branch += l.kind == SurfaceKind::kBranch;
      ground += l.kind == SurfaceKind::kGround;
      sky += l.kind == SurfaceKind::kNone;
      tape += l.marker >= 0;
    }
    const double n = static_cast<double>(r.labels.pixels.size());
    EXPECT_GT(branch / n, 0.02) << name;
    EXPECT_GT(ground / n, 0.1) << name;
    EXPECT_GT(sky / n, 0.1) << name;
    EXPECT_GT(tape, 20u) << name;
    // Tape pixels are red, bark pixels are not.
    double tape_red = 0, bark_red = 0;
    size_t bark = 0;
    for (size_t i = 0; i < r.labels.pixels.size(); ++i) {
      const uint8_t* c = &r.image.color.pixels[3 * i];
      const double redness = c[0] - 0.5 * (c[1] + c[2]);
      if (r.labels.pixels[i].marker >= 0) {
        tape_red += redness;
      } else if (r.labels.pixels[i].kind == SurfaceKind::kBranch) {
        bark_red += redness;
        ++bark;
      }
    }
    EXPECT_GT(tape_red / tape, 60.0) << name;
    EXPECT_LT(bark_red / bark, 30.0) << name;
  }
}

TEST(RgbdRenderer, AKnownCylinderMeasuresTheRightDepthWithTheModelledNoise) {
  const double radius = 0.1;
  const Tree tree = test::VerticalCylinder(0, 0, 3.0, radius);
  const SensorScene scene(tree, test::BareScene());
  const SensorModel sensor = SensorModel::AzureKinectNfov();
  const CameraIntrinsics k = sensor.Intrinsics();
  const DepthBiasField bias(sensor);
  double raw_std[2] = {0, 0};
  const double distances[2] = {1.0, 3.0};
  for (int which = 0; which < 2; ++which) {
    const double d = distances[which];
    const Eigen::Isometry3d camera = LookAt({d + radius, 0, 1.5}, {0, 0, 1.5});
    const RenderResult r = RenderRgbd(scene, sensor, camera, {.seed = 11, .frame = which});
    double sum = 0, sum2 = 0, raw = 0, raw2 = 0;
    int n = 0;
    for (int y = 0; y < k.height; ++y) {
      for (int x = 0; x < k.width; ++x) {
        const size_t i = static_cast<size_t>(y) * k.width + x;
        const double z = CylinderDepth(camera, k, x, y, radius);
        if (r.labels.pixels[i].kind != SurfaceKind::kBranch || z <= 0) continue;
        EXPECT_NEAR(r.labels.pixels[i].depth_m, z, 2e-6);  // the exact hit
        const DepthEffect effect = r.measurement.effects[i];
        if (effect != DepthEffect::kMeasured) continue;
        // Pixels facing the camera within ~25 degrees (away from the silhouette).
        const Eigen::Vector3d p = camera * k.Unproject(x, y, z);
        const Eigen::Vector3d to_camera = (camera.translation() - p).normalized();
        const double cos_incidence = Eigen::Vector3d(p.x(), p.y(), 0).normalized().dot(to_camera);
        if (cos_incidence < 0.9) continue;
        const double e = r.image.depth.pixels[i] * 0.001 - z - bias.At(z, x, y);
        const double sigma =
            std::sqrt(std::pow(sensor.DepthNoiseStd(z, cos_incidence), 2) + 1e-6 / 12);
        sum += e / sigma;
        sum2 += (e / sigma) * (e / sigma);
        raw += e;
        raw2 += e * e;
        ++n;
      }
    }
    ASSERT_GT(n, 2000) << d;
    const double mean = sum / n;
    const double std = std::sqrt(sum2 / n - mean * mean);
    // Mean and spread as modelled.
    EXPECT_NEAR(mean, 0.0, 5.0 / std::sqrt(n)) << d;
    EXPECT_NEAR(std, 1.0, 0.05) << d;
    raw_std[which] = std::sqrt(raw2 / n - (raw / n) * (raw / n));
    RecordProperty(which == 0 ? "raw_std_mm_at_1m" : "raw_std_mm_at_3m",
                   std::to_string(1000.0 * raw_std[which]));
  }
  // The spread grows from about 2.6 mm at 1 m to about 10.5 mm at 3 m.
  EXPECT_NEAR(raw_std[0], 0.0026, 0.0004);
  EXPECT_NEAR(raw_std[1], 0.0106, 0.0012);
}

TEST(RgbdRenderer, APlaneAtAKnownDistanceAndTilt) {
  SceneOptions o = test::BareScene();
  o.ground = true;
  const SensorScene scene(test::VerticalCylinder(30, 30, 1, 0.1), o);  // tree out of view
  const CameraIntrinsics k = SensorModel::AzureKinectNfov().Intrinsics();
  const double height = 1.2;
  const double pitch = 40.0 * std::numbers::pi / 180.0;
  const Eigen::Vector3d eye(0, 0, height);
  const Eigen::Isometry3d camera =
      LookAt(eye, eye + Eigen::Vector3d(std::cos(pitch), 0, -std::sin(pitch)));
  // An ideal sensor gives the plane's exact depth, quantised, at every pixel in range.
  const RenderResult ideal = RenderRgbd(scene, SensorModel::Ideal(), camera, {.seed = 1});
  int measured = 0;
  for (int y = 0; y < k.height; ++y) {
    for (int x = 0; x < k.width; ++x) {
      const Eigen::Vector3d d =
          camera.linear() * Eigen::Vector3d((x - k.cx) / k.fx, (y - k.cy) / k.fy, 1);
      const double z = d.z() < 0 ? height / -d.z() : 0.0;
      const double range = z * d.norm();
      const uint16_t depth = ideal.image.depth.at(x, y);
      if (z > 0 && range >= 0.5 + 0.002 && range <= 3.86 - 0.002) {
        ASSERT_NEAR(depth * 0.001, z, 0.0005 + 1e-9) << x << " " << y;
        ++measured;
      } else if (z > 0 && range >= 0.5 - 0.002 && range <= 3.86 + 0.002) {
        // Within a millimetre step of the range's ends: either.
      } else {
        ASSERT_EQ(depth, 0) << x << " " << y;
      }
    }
  }
  EXPECT_GT(measured, 100000);
  // The Azure model: a least-squares plane through the measured points is the ground.
  const RenderResult real = RenderRgbd(scene, SensorModel::AzureKinectNfov(), camera, {.seed = 1});
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> points;
  for (int y = 0; y < k.height; ++y) {
    for (int x = 0; x < k.width; ++x) {
      const size_t i = static_cast<size_t>(y) * k.width + x;
      if (real.measurement.effects[i] != DepthEffect::kMeasured) continue;
      points.push_back(camera * k.Unproject(x, y, real.image.depth.pixels[i] * 0.001));
      centroid += points.back();
    }
  }
  ASSERT_GT(points.size(), 100000u);
  centroid /= static_cast<double>(points.size());
  for (const Eigen::Vector3d& p : points) scatter += (p - centroid) * (p - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  const Eigen::Vector3d normal = solver.eigenvectors().col(0);
  EXPECT_LT(std::acos(std::min(1.0, std::abs(normal.z()))), 0.5 * std::numbers::pi / 180.0);
  EXPECT_NEAR(centroid.z(), 0.0, 0.008);  // the systematic error: a few millimetres
}

TEST(RgbdRenderer, NothingBeyondTheRangeInARealisticScene) {
  const Tree tree = test::Tree02();
  const SensorScene scene(tree, DefaultSceneOptions(tree, 2));
  const SensorModel sensor = SensorModel::AzureKinectNfov();
  const CameraIntrinsics k = sensor.Intrinsics();
  const RenderResult r = RenderRgbd(scene, sensor, LookAt({2.5, 0, 1.2}, {0, 0, 1.8}));
  int far_surfaces = 0;
  for (int y = 0; y < k.height; ++y) {
    for (int x = 0; x < k.width; ++x) {
      const size_t i = static_cast<size_t>(y) * k.width + x;
      const uint16_t d = r.image.depth.pixels[i];
      ASSERT_LE(d, 3860);
      const double true_range = k.Unproject(x, y, r.labels.pixels[i].depth_m).norm();
      if (true_range > 3.9) {
        ++far_surfaces;
        if (r.measurement.effects[i] != DepthEffect::kOutlier) {
          ASSERT_EQ(d, 0);
        }
      }
      if (d > 0) {
        ASSERT_LE(k.Unproject(x, y, d * 0.001).norm(), 3.86 + 1e-9);
      }
    }
  }
  EXPECT_GT(far_surfaces, 10000);  // the hedge and the far ground are there, but not measured
}

TEST(RgbdRenderer, ABranchUnderOneAndAHalfPixelsVanishesAndOneOfFivePixelsDoesNot) {
  const SensorModel sensor = SensorModel::AzureKinectNfov();
  const double f = sensor.FocalLengthPx();
  const double distance = 2.0;
  const Eigen::Isometry3d camera = LookAt({distance, 0, 1.5}, {0, 0, 1.5});
  struct Kept {
    double pixels = 0.0;   // share of the branch's pixels with a depth
    double columns = 0.0;  // share of the image columns it crosses with at least one depth
  };
  auto kept = [&](double width_px) {
    const double radius = width_px * distance / (2 * f);
    // Horizontal, across the view, centred on pixel row 288 (half a pixel below the centre).
    const double z = 1.5 - 0.5 * distance / f;
    const Tree twig = test::OneBranchTree({0, -1, z}, Eigen::Vector3d::UnitY(), 2.0, radius);
    const SensorScene scene(twig, test::BareScene());
    const RenderResult r = RenderRgbd(scene, sensor, camera, {.seed = 4});
    int labelled = 0, measured = 0, columns = 0, columns_measured = 0;
    for (int x = 0; x < r.labels.width; ++x) {
      bool on = false, any = false;
      for (int y = 0; y < r.labels.height; ++y) {
        if (r.labels.at(x, y).kind != SurfaceKind::kBranch) continue;
        ++labelled;
        on = true;
        const bool m = r.image.depth.at(x, y) > 0;
        measured += m;
        any = any || m;
      }
      columns += on;
      columns_measured += any;
    }
    EXPECT_GT(columns, 400) << width_px;
    return Kept{static_cast<double>(measured) / labelled,
                static_cast<double>(columns_measured) / columns};
  };
  const Kept thin = kept(1.0);
  EXPECT_LT(thin.pixels, 0.1);
  EXPECT_LT(thin.columns, 0.1);
  const Kept half = kept(1.5);  // the soft threshold: about half
  EXPECT_GT(half.pixels, 0.2);
  EXPECT_LT(half.pixels, 0.7);
  const Kept thick = kept(5.0);  // minus its grazing and edge pixels, all there
  EXPECT_GT(thick.pixels, 0.75);
  EXPECT_GT(thick.columns, 0.98);
}

TEST(RgbdRenderer, GrazingGroundDropsAndSteepGroundStays) {
  SceneOptions o = test::BareScene();
  o.ground = true;
  const SensorScene scene(test::VerticalCylinder(30, 30, 1, 0.1), o);
  SensorModel sensor = SensorModel::AzureKinectNfov();
  sensor.outlier_rate = 0.0;
  const CameraIntrinsics k = sensor.Intrinsics();
  const Eigen::Isometry3d camera = LookAt({0, 0, 0.2}, {5, 0, 0.2});
  const RenderResult r = RenderRgbd(scene, sensor, camera, {.seed = 8});
  int grazing = 0, grazing_measured = 0, steep = 0, steep_measured = 0;
  for (int y = 0; y < k.height; ++y) {
    for (int x = 0; x < k.width; ++x) {
      const size_t i = static_cast<size_t>(y) * k.width + x;
      if (r.labels.pixels[i].kind != SurfaceKind::kGround) continue;
      const Eigen::Vector3d d =
          camera.linear() * Eigen::Vector3d((x - k.cx) / k.fx, (y - k.cy) / k.fy, 1);
      const double incidence_deg = std::acos(std::abs(d.z()) / d.norm()) * 180 / std::numbers::pi;
      const double range = r.labels.pixels[i].depth_m * d.norm();
      if (range < 0.6 || range > 3.7) continue;
      if (incidence_deg > 85.0) {
        ++grazing;
        grazing_measured += r.image.depth.pixels[i] > 0;
      } else if (incidence_deg < 75.0) {
        ++steep;
        steep_measured += r.image.depth.pixels[i] > 0;
      }
    }
  }
  ASSERT_GT(grazing, 5000);
  ASSERT_GT(steep, 5000);
  EXPECT_EQ(grazing_measured, 0);
  EXPECT_GT(steep_measured, 0.97 * steep);
}

TEST(RgbdRenderer, FlyingPixelsAppearAtASilhouetteAndOnlyThere) {
  const double radius = 0.1;
  SceneOptions o = test::BareScene();
  o.boxes.push_back({.center = {-1.2, 0, 1.5}, .half_extent = {0.2, 3.0, 1.5}});  // a wall
  const SensorScene scene(test::VerticalCylinder(0, 0, 3.0, radius), o);
  SensorModel sensor = SensorModel::AzureKinectNfov();
  sensor.outlier_rate = 0.0;
  const CameraIntrinsics k = sensor.Intrinsics();
  const RenderResult r =
      RenderRgbd(scene, sensor, LookAt({1.5, 0, 1.0}, {0, 0, 1.0}), {.seed = 21});
  int off_surface = 0, edge_pixels = 0;
  for (int y = 0; y < k.height; ++y) {
    for (int x = 0; x < k.width; ++x) {
      const PixelLabel& l = r.labels.at(x, y);
      if (l.depth_m == 0) continue;
      const bool edge = NextToADiscontinuity(r.labels, x, y, 0.05);
      // Cylinder against wall (not against the sky around the wall).
      const bool silhouette = edge && l.kind == SurfaceKind::kBranch &&
                              (x > 0 && r.labels.at(x - 1, y).kind == SurfaceKind::kBackground);
      edge_pixels += silhouette;
      const uint16_t d = r.image.depth.at(x, y);
      if (d == 0) continue;
      if (std::abs(d * 0.001 - l.depth_m) > 0.05) {
        ++off_surface;
        ASSERT_TRUE(edge) << "a depth far from any surface away from a silhouette at " << x << " "
                          << y;
      }
    }
  }
  EXPECT_GT(edge_pixels, 300);
  // Half the edge pixels on both sides of both silhouettes fly (some of the cylinder's are
  // grazing and dropped first), and most of them more than 5 cm.
  EXPECT_GT(off_surface, 0.8 * edge_pixels);
}

TEST(RgbdRenderer, SameSeedSameBytesWhateverTheThreadsOtherSeedOtherNoise) {
  const Tree tree = test::Tree02WithMarkers();
  const SensorScene scene(tree, DefaultSceneOptions(tree, 5));
  const SensorModel sensor = SensorModel::AzureKinectNfov();
  const Eigen::Isometry3d camera = LookAt({2.5, 1.0, 1.4}, {0, 0, 2.0});
  auto render = [&](int threads, uint64_t seed) {
    tbb::task_arena arena(threads);
    RenderResult r;
    arena.execute([&] { r = RenderRgbd(scene, sensor, camera, {.seed = seed, .frame = 3}); });
    return r;
  };
  const RenderResult a = render(1, 1);
  const RenderResult b = render(2, 1);
  const RenderResult c = render(2, 2);
  EXPECT_EQ(EncodePng(a.image.color), EncodePng(b.image.color));
  EXPECT_EQ(EncodePng(a.image.depth), EncodePng(b.image.depth));
  EXPECT_NE(EncodePng(a.image.color), EncodePng(c.image.color));
  EXPECT_NE(EncodePng(a.image.depth), EncodePng(c.image.depth));
  ASSERT_EQ(a.markers.size(), b.markers.size());
  for (size_t m = 0; m < a.markers.size(); ++m) {
    EXPECT_EQ(a.markers[m].box.box, b.markers[m].box.box);
    EXPECT_EQ(a.markers[m].box.visible_pixels, b.markers[m].box.visible_pixels);
  }
  // The labels (the geometry) do not depend on the seed; only the noise does.
  for (size_t i = 0; i < a.labels.pixels.size(); ++i) {
    ASSERT_EQ(a.labels.pixels[i].branch, c.labels.pixels[i].branch);
  }
}

TEST(RgbdRenderer, TheHardSensorLosesAndCorruptsMore) {
  const Tree tree = test::Tree02WithMarkers();
  const SensorScene scene(tree, DefaultSceneOptions(tree, 6, true));
  const Eigen::Isometry3d camera = LookAt({2.8, -0.8, 1.3}, {0, 0, 1.9});
  const RenderResult normal = RenderRgbd(scene, SensorModel::AzureKinectNfov(), camera);
  const RenderResult hard = RenderRgbd(scene, SensorModel::Hard(), camera);
  const auto dir = test::TempDir();
  WritePng(hard.image.color, dir / "hard_color.png");
  WritePng(ColorizeDepth(hard.image.depth, {.near_m = 1.0}), dir / "hard_depth.png");
  for (DepthEffect e : {DepthEffect::kOutlier, DepthEffect::kThinDropout,
                        DepthEffect::kGrazingDropout, DepthEffect::kEdgeDropout}) {
    EXPECT_GT(hard.measurement.count(e), normal.measurement.count(e)) << ToString(e);
  }
  EXPECT_LT(hard.measurement.count(DepthEffect::kMeasured),
            normal.measurement.count(DepthEffect::kMeasured));
}

TEST(RgbdRenderer, BlankColourWithoutDepthAsTheSdkTransformationGives) {
  const Tree tree = test::VerticalCylinder(0, 0, 3.0, 0.1);
  const SensorScene scene(tree, test::BareScene());
  SensorModel sensor = SensorModel::AzureKinectNfov();
  sensor.blank_color_without_depth = true;
  const RenderResult r = RenderRgbd(scene, sensor, LookAt({1.5, 0, 1.5}, {0, 0, 1.5}));
  int blank = 0, coloured = 0;
  for (size_t i = 0; i < r.image.depth.pixels.size(); ++i) {
    const int sum = r.image.color.pixels[3 * i] + r.image.color.pixels[3 * i + 1] +
                    r.image.color.pixels[3 * i + 2];
    if (r.image.depth.pixels[i] == 0) {
      ASSERT_EQ(sum, 0);
      ++blank;
    } else {
      coloured += sum > 0;
    }
  }
  EXPECT_GT(blank, 100000);  // the sky
  EXPECT_GT(coloured, 20000);
}

TEST(RgbdRenderer, RefusesABadCameraOrSensor) {
  const Tree tree = test::VerticalCylinder(0, 0, 1, 0.1);
  const SensorScene scene(tree, test::BareScene());
  const SensorModel sensor = SensorModel::AzureKinectNfov();
  Eigen::Isometry3d nan = LookAt({2, 0, 0.5}, {0, 0, 0.5});
  nan.translation() = kNaN3;
  EXPECT_THROW(RenderRgbd(scene, sensor, nan), InputError);
  Eigen::Isometry3d skewed = LookAt({2, 0, 0.5}, {0, 0, 0.5});
  skewed.linear() *= 2.0;
  EXPECT_THROW(RenderRgbd(scene, sensor, skewed), InputError);
  SensorModel empty = sensor;
  empty.width = 0;
  EXPECT_THROW(RenderRgbd(scene, empty, LookAt({2, 0, 0.5}, {0, 0, 0.5})), InputError);
  SensorModel nan_noise = sensor;
  nan_noise.noise_base_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(RenderRgbd(scene, nan_noise, LookAt({2, 0, 0.5}, {0, 0, 0.5})), InputError);
  EXPECT_THROW(LookAt({1, 1, 1}, {1, 1, 1}), InputError);
  EXPECT_THROW(LookAt({0, 0, 0}, {0, 0, 5}), InputError);  // straight up: no image "up"
}

}  // namespace
}  // namespace simtree::synth
