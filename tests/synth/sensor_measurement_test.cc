#include "simtree/synth/detail/sensor_measurement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "simtree/core/error.h"

namespace simtree::synth {
namespace {

// A truth image of the sensor's size filled with one surface at depth z facing the camera.
DepthTruthImage Flat(const SensorModel& s, float z) {
  DepthTruthImage t(s.width, s.height);
  for (PixelTruth& p : t.pixels) p.depth_m = z;
  return t;
}

TEST(MeasureDepth, OutliersAppearAtTheSetRateAnywhereInRange) {
  SensorModel s = SensorModel::Ideal();
  s.outlier_rate = 0.01;
  const DepthTruthImage sky(s.width, s.height);  // nothing hit anywhere
  const MeasureResult r = MeasureDepth(s, sky, {.seed = 3, .frame = 1});
  const double n = static_cast<double>(sky.pixels.size());
  const double expected = s.outlier_rate * n;
  const double sigma = std::sqrt(n * s.outlier_rate * (1 - s.outlier_rate));
  EXPECT_NEAR(static_cast<double>(r.count(DepthEffect::kOutlier)), expected, 5 * sigma);
  EXPECT_EQ(r.count(DepthEffect::kNoReturn) + r.count(DepthEffect::kOutlier),
            static_cast<int64_t>(n));
  const CameraIntrinsics k = s.Intrinsics();
  int nonzero = 0;
  double smallest = 1e9, largest = 0;
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      const uint16_t d = r.depth.at(x, y);
      if (d == 0) continue;
      ++nonzero;
      const double range = k.Unproject(x, y, d * 0.001).norm();
      smallest = std::min(smallest, range);
      largest = std::max(largest, range);
    }
  }
  EXPECT_EQ(nonzero, r.count(DepthEffect::kOutlier));
  EXPECT_GE(smallest, s.min_range_m);
  EXPECT_LE(largest, s.max_range_m);
  EXPECT_LT(smallest, 0.7);  // spread over the whole range
  EXPECT_GT(largest, 3.6);
}

TEST(MeasureDepth, NothingOutsideTheRange) {
  const SensorModel s = SensorModel::AzureKinectNfov();
  const CameraIntrinsics k = s.Intrinsics();
  for (float z : {0.3f, 0.45f, 3.7f, 3.86f, 4.2f, 6.0f}) {
    const MeasureResult r = MeasureDepth(s, Flat(s, z), {.seed = 1, .frame = 0});
    for (int y = 0; y < s.height; ++y) {
      for (int x = 0; x < s.width; ++x) {
        const uint16_t d = r.depth.at(x, y);
        ASSERT_LE(d, 3860);
        if (d == 0) continue;
        const double range = k.Unproject(x, y, d * 0.001).norm();
        ASSERT_LE(range, s.max_range_m + 1e-9) << z;
        ASSERT_GE(range, s.min_range_m - 1e-9) << z;
        const double true_range = k.Unproject(x, y, z).norm();
        if (r.effects[static_cast<size_t>(y) * s.width + x] != DepthEffect::kOutlier) {
          ASSERT_LE(true_range, s.max_range_m) << "a surface beyond range was measured";
          ASSERT_GE(true_range, s.min_range_m) << "a surface nearer than min range was measured";
        }
      }
    }
  }
}

TEST(MeasureDepth, QuantisesToMillimetresAndAddsTheModelledNoise) {
  SensorModel s = SensorModel::AzureKinectNfov();
  s.outlier_rate = 0.0;
  const DepthBiasField bias(s);
  for (float z : {1.0f, 3.0f}) {
    const MeasureResult r = MeasureDepth(s, Flat(s, z), {.seed = 5, .frame = 2});
    double sum = 0, sum2 = 0;
    int n = 0;
    for (int y = 0; y < s.height; ++y) {
      for (int x = 0; x < s.width; ++x) {
        const uint16_t d = r.depth.at(x, y);
        if (d == 0) continue;
        const double e = d * 0.001 - z - bias.At(z, x, y);
        sum += e;
        sum2 += e * e;
        ++n;
      }
    }
    const double mean = sum / n;
    const double std = std::sqrt(sum2 / n - mean * mean);
    const double sigma = std::sqrt(std::pow(s.DepthNoiseStd(z, 1.0), 2) + 1e-6 / 12.0);
    EXPECT_GT(n, 250000);
    EXPECT_NEAR(mean, 0.0, 5 * sigma / std::sqrt(n)) << z;
    EXPECT_NEAR(std, sigma, 0.02 * sigma) << z;
  }
}

TEST(MeasureDepth, FlyingPixelsOnlyOnADepthStepAndBetweenItsSides) {
  SensorModel s = SensorModel::AzureKinectNfov();
  s.outlier_rate = 0.0;
  s.bias_offset_m = s.bias_scale = s.bias_pattern_m = 0.0;
  DepthTruthImage t(s.width, s.height);
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) t.at(x, y).depth_m = x < 300 ? 1.0f : 2.0f;
  }
  const MeasureResult r = MeasureDepth(s, t, {.seed = 9, .frame = 0});
  int flying = 0;
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      const DepthEffect e = r.effects[static_cast<size_t>(y) * s.width + x];
      const double d = r.depth.at(x, y) * 0.001;
      if (e == DepthEffect::kFlyingPixel || e == DepthEffect::kEdgeDropout) {
        ASSERT_TRUE(x == 299 || x == 300) << x;  // only on the step
      }
      if (e == DepthEffect::kFlyingPixel) {
        ++flying;
        ASSERT_GT(d, 1.0 - 0.02);  // between the sides (plus a few sigma of noise)
        ASSERT_LT(d, 2.0 + 0.04);
      } else if (d > 0) {
        const double z = t.at(x, y).depth_m;
        ASSERT_NEAR(d, z, 6 * s.DepthNoiseStd(z, 1.0) + 0.001) << x << " " << y;
      }
    }
  }
  // Two columns of edge pixels, half of them flying.
  EXPECT_NEAR(flying, 0.5 * 2 * s.height, 0.1 * 2 * s.height);
  EXPECT_EQ(flying, r.count(DepthEffect::kFlyingPixel));
}

TEST(MeasureDepth, SameSeedSameImageOtherSeedOtherNoise) {
  const SensorModel s = SensorModel::AzureKinectNfov();
  const DepthTruthImage t = Flat(s, 2.0f);
  const MeasureResult a = MeasureDepth(s, t, {.seed = 1, .frame = 4});
  const MeasureResult b = MeasureDepth(s, t, {.seed = 1, .frame = 4});
  const MeasureResult c = MeasureDepth(s, t, {.seed = 2, .frame = 4});
  const MeasureResult d = MeasureDepth(s, t, {.seed = 1, .frame = 5});
  EXPECT_EQ(a.depth, b.depth);
  EXPECT_NE(a.depth, c.depth);
  EXPECT_NE(a.depth, d.depth);
}

TEST(MeasureDepth, RefusesATruthOfTheWrongSizeOrWithABadDepth) {
  const SensorModel s = SensorModel::AzureKinectNfov();
  EXPECT_THROW(MeasureDepth(s, DepthTruthImage(320, 288)), InputError);
  EXPECT_THROW(MeasureDepth(s, DepthTruthImage()), InputError);
  DepthTruthImage t = Flat(s, 1.0f);
  t.at(10, 20).depth_m = std::numeric_limits<float>::quiet_NaN();
  try {
    MeasureDepth(s, t);
    ADD_FAILURE() << "accepted NaN";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("(10, 20)"), std::string::npos) << e.what();
  }
  t.at(10, 20).depth_m = -1.0f;
  EXPECT_THROW(MeasureDepth(s, t), InputError);
  SensorModel bad = s;
  bad.width = 0;
  EXPECT_THROW(MeasureDepth(bad, DepthTruthImage()), InputError);
}

}  // namespace
}  // namespace simtree::synth
