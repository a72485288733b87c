#include "simtree/tracking/detail/color_model.h"

#include <gtest/gtest.h>

#include "simtree/core/error.h"

namespace simtree::tracking::detail {
namespace {

TEST(ColorModel, RedSpansTheHueWrap) {
  const TapeColorModel red = ColorModelFromName("red");
  EXPECT_TRUE(red.Contains(200, 20, 45));  // hue ~352
  EXPECT_TRUE(red.Contains(200, 45, 20));  // hue ~9
  EXPECT_FALSE(red.Contains(40, 200, 40));
}

TEST(ColorModel, HoldsUnderShadeAndSunButRejectsBarkAndGrey) {
  const TapeColorModel red = ColorModelFromName("auto");
  EXPECT_TRUE(red.Contains(70, 8, 10));     // deep shade
  EXPECT_TRUE(red.Contains(255, 90, 95));   // sunlit, washed out
  EXPECT_FALSE(red.Contains(110, 80, 60));  // brown bark
  EXPECT_FALSE(red.Contains(120, 120, 120));
  EXPECT_FALSE(red.Contains(10, 1, 1));  // too dark to have a hue
}

TEST(ColorModel, CameraOrangeBarkIsNotTapeButFaintTapeNearItsHueIs) {
  const TapeColorModel red = ColorModelFromName("red");
  // Bark a camera's white balance and chroma smearing turned orange-red: hue 20, saturation 0.5,
  // inside the hue interval and above the least saturation.
  EXPECT_FALSE(red.Contains(120, 80, 60));
  EXPECT_LT(red.Weight(120, 80, 60), 0.1f);  // 0.55 with a flat saturation threshold
  // Tape as faint but at its own hue (-5 degrees): still tape.
  EXPECT_TRUE(red.Contains(120, 60, 65));
  // Far from the hue centre only a strongly saturated pixel counts.
  EXPECT_TRUE(red.Contains(200, 70, 20));  // hue 20, saturation 0.9
}

TEST(ColorModel, WeightGradesMixedPixels) {
  const TapeColorModel red = ColorModelFromName("red");
  const float full = red.Weight(200, 25, 30);
  const float half = red.Weight(150, 60, 60);  // tape washed out by grey
  const float none = red.Weight(100, 85, 60);
  EXPECT_FLOAT_EQ(full, 1.0f);
  EXPECT_GT(half, 0.0f);
  EXPECT_LT(half, full);
  EXPECT_FLOAT_EQ(none, 0.0f);
}

TEST(ColorModel, NamesAndHexColours) {
  EXPECT_NEAR(ColorModelFromName("green").hue_deg, 120.0, 1e-9);
  EXPECT_NEAR(ColorModelFromName("#0000ff").hue_deg, 240.0, 1e-3);
  EXPECT_THROW(ColorModelFromName("purple-ish"), InputError);
  EXPECT_THROW(ColorModelFromName("#808080"), InputError);  // grey: no hue
}

TEST(ColorModel, FitFollowsTheTapeAroundTheInitPixels) {
  RgbImage image(20, 20, 100);
  for (int y = 8; y < 12; ++y) {
    for (int x = 8; x < 12; ++x) {
      image.at(x, y, 0) = 190;
      image.at(x, y, 1) = 60;  // an orange-red: hue ~14
      image.at(x, y, 2) = 30;
    }
  }
  int found = 0;
  const TapeColorModel fit =
      FitColorModel(ColorModelFromName("auto"), image, {Eigen::Vector2d(9.5, 9.5)}, 4, 12, &found);
  EXPECT_EQ(found, 16);
  EXPECT_NEAR(fit.hue_deg, 11.25, 1.0);
  EXPECT_TRUE(fit.Contains(190, 60, 30));
}

TEST(ColorModel, ExtendsAwayFromTheBarkTowardsASkyMixedTape) {
  // Orange-brown bark everywhere (hue +25, saturation 0.3) and, at the click, a dark tape that
  // chroma mixed with sky turned magenta (hue -30, saturation 0.55, value 60).
  RgbImage image(40, 40, 0);
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 40; ++x) {
      image.at(x, y, 0) = 120;
      image.at(x, y, 1) = 99;
      image.at(x, y, 2) = 84;
    }
  }
  for (int y = 18; y < 21; ++y) {
    image.at(20, y, 0) = 60;
    image.at(20, y, 1) = 27;
    image.at(20, y, 2) = 44;
  }
  const TapeColorModel red = ColorModelFromName("red");
  EXPECT_FALSE(red.Contains(60, 27, 44));
  const TapeColorModel fit = ExtendAwayFromBackground(red, image, {Eigen::Vector2d(20, 19)}, 3);
  EXPECT_EQ(fit.extra_side, -1);
  EXPECT_NEAR(fit.extra_hue_deg, 30.0 - red.hue_core_deg, 1.0);
  EXPECT_TRUE(fit.Contains(60, 27, 44));
  // The bark's side is untouched: a saturated orange stays out.
  EXPECT_FALSE(fit.Contains(150, 109, 68));
  EXPECT_FALSE(fit.Contains(120, 99, 84));
}

}  // namespace
}  // namespace simtree::tracking::detail
