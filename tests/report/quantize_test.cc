#include "simtree/report/detail/quantize.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "simtree/core/error.h"

namespace simtree::report {
namespace {

TEST(Quantise, RoundTripIsWithinHalfAStep) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> x(-1.2f, 1.5f), y(-0.3f, 0.4f), z(0.0f, 12.0f);
  std::vector<float> xyz;
  for (int i = 0; i < 5000; ++i) xyz.insert(xyz.end(), {x(rng), y(rng), z(rng)});
  const QuantisationBox box = QuantisationBox::Of(xyz);
  std::string bytes;
  AppendQuantised(xyz, box, bytes);
  ASSERT_EQ(bytes.size(), xyz.size() * 2);
  const std::vector<float> back = Dequantise(bytes, box);
  ASSERT_EQ(back.size(), xyz.size());
  for (size_t i = 0; i < xyz.size(); ++i) {
    const int axis = static_cast<int>(i % 3);
    // Half a step, plus float rounding of the decoded value.
    EXPECT_LE(std::abs(back[i] - xyz[i]), 0.5 * box.step[axis] + 2e-6) << i;
  }
  // 12 m over 65535 levels: a step of 0.18 mm.
  EXPECT_NEAR(box.step.z(), 12.0 / kQuantisationLevels, 1e-5);
}

TEST(Quantise, ABoxGrowsToHoldLaterFrames) {
  std::vector<float> first = {0, 0, 0, 1, 1, 1};
  std::vector<float> later = {-1, 0.5f, 2};
  QuantisationBox box = QuantisationBox::Of(first);
  box.Include(later);
  EXPECT_EQ(box.min.x(), -1.0);
  std::string bytes;
  AppendQuantised(later, box, bytes);
  const std::vector<float> back = Dequantise(bytes, box);
  EXPECT_NEAR(back[0], -1.0f, 1e-5);
  EXPECT_NEAR(back[2], 2.0f, 1e-4);
}

TEST(Quantise, FlatAxesAndOddValuesDoNotBreakIt) {
  std::vector<float> xyz = {1, 2, 3, 1, 2, 3};  // no extent at all
  const QuantisationBox box = QuantisationBox::Of(xyz);
  EXPECT_GT(box.step.minCoeff(), 0.0);
  std::string bytes;
  AppendQuantised(xyz, box, bytes);
  EXPECT_FLOAT_EQ(Dequantise(bytes, box)[1], 2.0f);
  EXPECT_EQ(box.Encode(0, std::numeric_limits<double>::quiet_NaN()), 0);
  EXPECT_EQ(box.Encode(0, 1e9), kQuantisationLevels);  // clamped
  EXPECT_THROW(QuantisationBox::Of(std::vector<float>{1, 2}), InputError);
  EXPECT_THROW(Dequantise("abcd", box), InputError);
}

}  // namespace
}  // namespace simtree::report
