#include "simtree/tracking/find_tapes.h"

#include <gtest/gtest.h>

#include "drawn_stream.h"
#include "simtree/core/error.h"

namespace simtree::tracking {
namespace {

TEST(FindTapes, EveryDrawnBandWithItsCentreAndWidth) {
  test::DrawnStream s;
  const std::vector<Eigen::Vector3d> markers = {{-0.15, 0.05, 1.5}, {0.1, -0.08, 1.7}};
  const RgbdImage frame = test::DrawFrame(s, markers);
  const std::vector<TapeSighting> tapes = FindTapes(frame, {});
  ASSERT_EQ(tapes.size(), 2u);
  std::vector<Eigen::Vector2d> pixels;
  for (const Eigen::Vector3d& p : markers) pixels.push_back(s.intrinsics.Project(p));
  const std::vector<int> at = TapesAtPixels(tapes, pixels, frame);
  ASSERT_EQ(at.size(), 2u);
  ASSERT_GE(at[0], 0);
  ASSERT_GE(at[1], 0);
  EXPECT_NE(at[0], at[1]);
  for (int m = 0; m < 2; ++m) {
    const TapeSighting& tape = tapes[at[m]];
    EXPECT_LT((tape.center - pixels[m]).norm(), 0.3);
    // The band is the branch's width across and the tape's length along it.
    const auto box = test::DrawnBox(s, markers[m]);
    EXPECT_NEAR(tape.width_px, box[2], 0.2 * box[2]) << "marker " << m;
    EXPECT_NEAR(tape.length_px, box[3], 0.2 * box[3]) << "marker " << m;
    EXPECT_GT(tape.pixel_count, 0);
  }
}

TEST(FindTapes, TapesCrossingAtDifferentDepthsStayTwo) {
  test::DrawnStream s;
  const RgbdImage frame = test::DrawFrame(s, {{0.0, 0.0, 1.5}, {0.01, 0.03, 1.9}});
  EXPECT_EQ(FindTapes(frame, {}).size(), 2u);
}

TEST(FindTapes, APixelWithNoTapeNearItMatchesNothing) {
  test::DrawnStream s;
  const RgbdImage frame = test::DrawFrame(s, {{0.0, 0.0, 1.5}});
  const std::vector<TapeSighting> tapes = FindTapes(frame, {});
  ASSERT_EQ(tapes.size(), 1u);
  const std::vector<int> at = TapesAtPixels(tapes, {{20.0, 20.0}}, frame);
  EXPECT_EQ(at, std::vector<int>{-1});
}

TEST(FindTapes, AnotherColourFindsNoRedTape) {
  test::DrawnStream s;
  const RgbdImage frame = test::DrawFrame(s, {{0.0, 0.0, 1.5}});
  FindTapesOptions blue;
  blue.color = "blue";
  EXPECT_TRUE(FindTapes(frame, blue).empty());
}

TEST(FindTapes, AnUnknownColourIsRefusedByName) {
  FindTapesOptions options;
  options.color = "purple-ish";
  try {
    options.Validate();
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("purple-ish"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace simtree::tracking
