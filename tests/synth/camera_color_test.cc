// The camera's colour pipeline: seeded and deterministic, exposure drifting within its amplitude
// and stepping where asked, noise of the asked size, JPEG with halved chroma smearing a thin red
// line, and options out of range refused by name.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "simtree/core/error.h"
#include "simtree/synth/detail/camera_color.h"
#include "test_util.h"

namespace simtree::synth {
namespace {

RgbImage Flat(int w, int h, uint8_t r, uint8_t g, uint8_t b) {
  RgbImage image(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      image.at(x, y, 0) = r;
      image.at(x, y, 1) = g;
      image.at(x, y, 2) = b;
    }
  }
  return image;
}

double MeanChannel(const RgbImage& image, int c) {
  double sum = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) sum += image.at(x, y, c);
  }
  return sum / static_cast<double>(image.pixel_count());
}

TEST(CameraColor, SameSeedSameBytesAnotherSeedOthers) {
  const RgbImage input = Flat(64, 48, 120, 90, 60);
  RgbImage a = input, b = input, c = input;
  CameraColor(CameraColorOptions{}, 3).Apply(1.0, 5, a);
  CameraColor(CameraColorOptions{}, 3).Apply(1.0, 5, b);
  CameraColor(CameraColorOptions{}, 4).Apply(1.0, 5, c);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(CameraColor, ExposureDriftsWithinItsAmplitudeAndStepsWhereAsked) {
  CameraColorOptions options;
  options.exposure_drift_stops = 0.2;
  const CameraColor camera(options, 1);
  double lo = 1e9, hi = 0;
  for (double t = 0; t < 20; t += 0.05) {
    lo = std::min(lo, camera.ExposureGain(t));
    hi = std::max(hi, camera.ExposureGain(t));
  }
  EXPECT_GE(lo, std::exp2(-0.2) - 1e-12);
  EXPECT_LE(hi, std::exp2(0.2) + 1e-12);
  EXPECT_GT(hi / lo, std::exp2(0.15));  // it does drift

  const CameraColor stepped(CameraColorOptions::WithExposureStep(5.0), 1);
  EXPECT_NEAR(stepped.ExposureGain(4.9) / camera.ExposureGain(4.9), 1.0, 1e-12);
  EXPECT_NEAR(stepped.ExposureGain(6.0) / camera.ExposureGain(6.0), std::exp2(-0.8), 1e-12);
}

TEST(CameraColor, WhiteBalanceAndNoiseHaveTheAskedSize) {
  CameraColorOptions options;
  options.exposure_drift_stops = 0.0;
  options.defocus_sigma_px = 0.0;
  options.jpeg_quality = 0;
  options.read_noise_std = 2.0;
  options.shot_noise_gain = 0.0;
  options.white_balance_error = 0.0;
  RgbImage image = Flat(200, 200, 100, 100, 100);
  CameraColor(options, 7).Apply(0.0, 0, image);
  double sum_sq = 0;
  for (uint8_t v : image.pixels) sum_sq += (v - 100.0) * (v - 100.0);
  EXPECT_NEAR(std::sqrt(sum_sq / image.pixels.size()), 2.0, 0.15);

  options.read_noise_std = 0.0;
  options.white_balance_error = 0.1;
  double spread = 0;
  for (uint64_t seed = 0; seed < 40; ++seed) {
    const CameraColor camera(options, seed);
    EXPECT_EQ(camera.white_balance()[1], 1.0);
    RgbImage grey = Flat(8, 8, 100, 100, 100);
    camera.Apply(0.0, 0, grey);
    EXPECT_NEAR(MeanChannel(grey, 0), 100.0 * camera.white_balance()[0], 0.51);
    spread += std::pow(std::log(camera.white_balance()[0]), 2);
  }
  EXPECT_NEAR(std::sqrt(spread / 40), 0.1, 0.04);
}

// A two-pixel red line on grey keeps its colour without compression; halved chroma and JPEG
// wash it out, 4:2:0 more than 4:2:2.
TEST(CameraColor, JpegWithHalvedChromaWashesOutAThinRedLine) {
  RgbImage image = Flat(64, 64, 110, 110, 100);
  for (int y = 0; y < 64; ++y) {
    for (int x = 31; x < 33; ++x) {
      image.at(x, y, 0) = 200;
      image.at(x, y, 1) = 30;
      image.at(x, y, 2) = 30;
    }
  }
  const auto redness = [](const RgbImage& im) {
    double sum = 0;
    for (int y = 8; y < 56; ++y) {
      for (int x = 31; x < 33; ++x) sum += im.at(x, y, 0) - 0.5 * (im.at(x, y, 1) + im.at(x, y, 2));
    }
    return sum / (48 * 2);
  };
  const double clean = redness(image);
  const double q422 = redness(JpegRoundTrip(image, 85, true));
  const double q420 = redness(JpegRoundTrip(image, 85, false));
  EXPECT_NEAR(clean, 170.0, 1e-9);
  EXPECT_LT(q422, 0.9 * clean);
  EXPECT_LT(q420, q422 + 1.0);
  // A flat image survives nearly unchanged.
  const RgbImage flat = Flat(32, 32, 90, 120, 60);
  const RgbImage back = JpegRoundTrip(flat, 85, true);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(MeanChannel(back, c), MeanChannel(flat, c), 2.0);
}

TEST(CameraColor, OptionsOutOfRangeAreRefusedByName) {
  CameraColorOptions options;
  options.jpeg_quality = 101;
  EXPECT_THAT(test::ErrorOf([&] { options.Validate(); }), ::testing::HasSubstr("jpeg_quality"));
  options = {};
  options.defocus_sigma_px = -1;
  EXPECT_THAT(test::ErrorOf([&] { CameraColor(options, 1); }),
              ::testing::HasSubstr("defocus_sigma_px"));
  options = {};
  options.exposure_steps.push_back({.time_s = 1, .stops = 9});
  EXPECT_THAT(test::ErrorOf([&] { options.Validate(); }),
              ::testing::HasSubstr("exposure_steps.stops"));
  EXPECT_THAT(test::ErrorOf([&] { JpegRoundTrip(RgbImage(4, 4), 0, true); }),
              ::testing::HasSubstr("quality"));
}

}  // namespace
}  // namespace simtree::synth
