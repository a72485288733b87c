#include "simtree/synth/detail/sensor_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "simtree/core/error.h"

namespace simtree::synth {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

TEST(SensorModel, IntrinsicsAreTheNfovUnbinnedImageWithSquarePixels) {
  const SensorModel s = SensorModel::AzureKinectNfov();
  const CameraIntrinsics k = s.Intrinsics();
  EXPECT_EQ(k.width, 640);
  EXPECT_EQ(k.height, 576);
  EXPECT_DOUBLE_EQ(k.fx, k.fy);
  EXPECT_DOUBLE_EQ(k.cx, 319.5);
  EXPECT_DOUBLE_EQ(k.cy, 287.5);
  EXPECT_DOUBLE_EQ(k.depth_scale_m, 0.001);
  // About 75 x 65 degrees: the geometric mean of the two focal lengths the angles give.
  const double fx = 320.0 / std::tan(37.5 * kDegree);
  const double fy = 288.0 / std::tan(32.5 * kDegree);
  EXPECT_NEAR(k.fx, std::sqrt(fx * fy), 1e-9);
  EXPECT_NEAR(k.HorizontalFov() / kDegree, 72.8, 0.05);
  EXPECT_NEAR(k.VerticalFov() / kDegree, 67.1, 0.05);
  EXPECT_DOUBLE_EQ(s.frame_rate_hz, 30.0);
  EXPECT_DOUBLE_EQ(s.min_range_m, 0.5);
  EXPECT_DOUBLE_EQ(s.max_range_m, 3.86);
}

TEST(SensorModel, RandomErrorGrowsWithDistanceAndIncidenceWithinTheHardwareSpec) {
  const SensorModel s = SensorModel::AzureKinectNfov();
  EXPECT_NEAR(s.DepthNoiseStd(1.0, 1.0), 0.0025, 1e-12);
  EXPECT_NEAR(s.DepthNoiseStd(3.0, 1.0), 0.0105, 1e-12);
  EXPECT_LT(s.DepthNoiseStd(1.0, 1.0), s.DepthNoiseStd(2.0, 1.0));
  EXPECT_LT(s.DepthNoiseStd(2.0, 1.0), s.DepthNoiseStd(2.0, std::cos(60 * kDegree)));
  EXPECT_NEAR(s.DepthNoiseStd(2.0, 0.5), 2.0 * s.DepthNoiseStd(2.0, 1.0), 1e-12);
  // Azure Kinect hardware spec: random error <= 17 mm (one sigma) over the operating range.
  EXPECT_LE(s.DepthNoiseStd(s.max_range_m, 1.0), 0.017);
  const SensorModel hard = SensorModel::Hard();
  for (double z : {0.5, 1.0, 2.0, 3.86}) {
    EXPECT_GT(hard.DepthNoiseStd(z, 0.8), s.DepthNoiseStd(z, 0.8)) << z;
  }
  EXPECT_EQ(SensorModel::Ideal().DepthNoiseStd(3.0, 0.1), 0.0);
}

TEST(SensorModel, SystematicErrorStaysWithinTheHardwareSpec) {
  // Spec: systematic error < 11 mm + 0.1% of the distance.
  for (const SensorModel& s : {SensorModel::AzureKinectNfov(), SensorModel::Hard()}) {
    const DepthBiasField bias(s);
    double smallest = 1.0, largest = -1.0;
    for (int y = 0; y < s.height; y += 7) {
      for (int x = 0; x < s.width; x += 7) {
        for (double z : {0.5, 2.0, 3.86}) {
          const double b = bias.At(z, x, y);
          EXPECT_LT(std::abs(b), 0.011 + 0.001 * z) << s.name << " " << x << " " << y;
          smallest = std::min(smallest, bias.Pattern(x, y));
          largest = std::max(largest, bias.Pattern(x, y));
        }
      }
    }
    // The pattern varies across the image (it is not a constant) within its amplitude.
    EXPECT_GT(largest - smallest, 0.3 * s.bias_pattern_m) << s.name;
    EXPECT_LE(std::max(-smallest, largest), s.bias_pattern_m + 1e-12) << s.name;
  }
  const DepthBiasField ideal(SensorModel::Ideal());
  EXPECT_EQ(ideal.At(3.0, 100, 100), 0.0);
}

TEST(SensorModel, ThinCurvesFadeOutSoftlyAroundOneAndAHalfPixels) {
  const SensorModel s = SensorModel::AzureKinectNfov();
  EXPECT_NEAR(s.ThinKeepProbability(1.5), 0.5, 1e-12);
  EXPECT_LT(s.ThinKeepProbability(1.0), 0.05);
  EXPECT_GT(s.ThinKeepProbability(2.0), 0.95);
  EXPECT_GT(s.ThinKeepProbability(5.0), 0.999999);
  EXPECT_EQ(SensorModel::Ideal().ThinKeepProbability(0.01), 1.0);
}

TEST(SensorModel, GrazingSurfacesDropBetweenTheTwoAngles) {
  const SensorModel s = SensorModel::AzureKinectNfov();
  EXPECT_EQ(s.GrazingKeepProbability(std::cos(60 * kDegree)), 1.0);
  EXPECT_EQ(s.GrazingKeepProbability(std::cos(75 * kDegree)), 1.0);
  EXPECT_NEAR(s.GrazingKeepProbability(std::cos(80 * kDegree)), 0.5, 1e-9);
  EXPECT_EQ(s.GrazingKeepProbability(std::cos(86 * kDegree)), 0.0);
  EXPECT_EQ(SensorModel::Ideal().GrazingKeepProbability(0.0), 1.0);
}

TEST(SensorModel, ValidationNamesTheField) {
  EXPECT_NO_THROW(ValidateSensorModel(SensorModel::AzureKinectNfov(), "s"));
  EXPECT_NO_THROW(ValidateSensorModel(SensorModel::Hard(), "s"));
  EXPECT_NO_THROW(ValidateSensorModel(SensorModel::Ideal(), "s"));
  auto expect_field = [](SensorModel s, const std::string& field) {
    try {
      ValidateSensorModel(s, "sensor.json");
      ADD_FAILURE() << "accepted a bad " << field;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), field) << e.what();
      EXPECT_EQ(e.source(), "sensor.json");
    }
  };
  SensorModel s = SensorModel::AzureKinectNfov();
  s.width = 0;
  expect_field(s, "width");
  s = SensorModel::AzureKinectNfov();
  s.height = -5;
  expect_field(s, "height");
  s = SensorModel::AzureKinectNfov();
  s.noise_base_m = std::numeric_limits<double>::quiet_NaN();
  expect_field(s, "noise_base_m");
  s = SensorModel::AzureKinectNfov();
  s.noise_quadratic_per_m2 = -0.001;
  expect_field(s, "noise_quadratic_per_m2");
  s = SensorModel::AzureKinectNfov();
  s.outlier_rate = 1.5;
  expect_field(s, "outlier_rate");
  s = SensorModel::AzureKinectNfov();
  s.max_range_m = 0.4;
  expect_field(s, "max_range_m");
  s = SensorModel::AzureKinectNfov();
  s.horizontal_fov_deg = 180.0;
  expect_field(s, "horizontal_fov_deg");
  s = SensorModel::AzureKinectNfov();
  s.grazing_full_deg = 70.0;  // before the start
  expect_field(s, "grazing_full_deg");
  s = SensorModel::AzureKinectNfov();
  s.quantization_m = 0.0;
  expect_field(s, "quantization_m");
  s = SensorModel::AzureKinectNfov();
  s.flying_pixel_probability = 0.9;  // with 0.2 edge dropout: more than certain
  expect_field(s, "flying_pixel_probability");
}

}  // namespace
}  // namespace simtree::synth
