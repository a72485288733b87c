// pull/init.json's simulated clicks: near the tape band's box centre, only for visible markers,
// seeded, inside the image, and read back by the io library.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "simtree/core/error.h"
#include "simtree/io/track_init.h"
#include "simtree/synth/detail/init_clicks.h"
#include "test_util.h"

namespace simtree::synth {
namespace {

MarkerBox2d Box(int id, bool visible, double x, double y, double w = 6.0, double h = 7.0) {
  MarkerBox2d b;
  b.id = id;
  b.visible = visible;
  b.box = {x, y, w, h};
  return b;
}

// Frame 0 shows markers 0, 2 and 3; marker 1 is hidden.
std::vector<MarkerFrame2d> Frames() {
  MarkerFrame2d f;
  f.frame = 0;
  f.markers = {Box(0, true, 100.5, 200.5), Box(1, false, 300, 300), Box(2, true, 400, 50),
               Box(3, true, 630, 570, 9.5, 5.5)};
  MarkerFrame2d g = f;
  g.frame = 1;
  return {f, g};
}

Eigen::Vector2d Centre(const MarkerBox2d& b) {
  return {b.box[0] + 0.5 * b.box[2], b.box[1] + 0.5 * b.box[3]};
}

TEST(InitClicks, WithoutNoiseTheClicksAreTheBoxCentresOfVisibleMarkers) {
  const std::vector<MarkerFrame2d> frames = Frames();
  const TrackInit init = SimulateInitClicks(frames, 640, 576, {.noise_px = 0.0, .seed = 1});
  EXPECT_EQ(init.frame, 0);
  ASSERT_EQ(init.markers.size(), 3u);
  EXPECT_EQ(init.markers[0].id, 0);
  EXPECT_EQ(init.markers[1].id, 2);
  EXPECT_EQ(init.markers[2].id, 3);
  EXPECT_LT((init.markers[0].pixel - Centre(frames[0].markers[0])).norm(), 1e-12);
  EXPECT_LT((init.markers[1].pixel - Centre(frames[0].markers[2])).norm(), 1e-12);
}

TEST(InitClicks, ClicksMissByAboutTheNoiseAndStayInsideTheImage) {
  // Many markers, so the spread can be measured.
  MarkerFrame2d f;
  for (int id = 0; id < 400; ++id) f.markers.push_back(Box(id, true, 20 + id, 100));
  f.markers.push_back(Box(400, true, 636, 572, 4, 4));  // at the corner: clamped inside
  const TrackInit init = SimulateInitClicks({f}, 640, 576, {.noise_px = 1.5, .seed = 9});
  ASSERT_EQ(init.markers.size(), 401u);
  double sum_sq = 0.0;
  for (int id = 0; id < 400; ++id) {
    const Eigen::Vector2d error = init.markers[id].pixel - Centre(f.markers[id]);
    EXPECT_LT(error.norm(), 4.0 * 1.5 * std::sqrt(2.0)) << id;  // within a few px
    sum_sq += error.squaredNorm();
  }
  const double std_per_axis = std::sqrt(sum_sq / (2 * 400));
  EXPECT_NEAR(std_per_axis, 1.5, 0.15);
  const Eigen::Vector2d corner = init.markers[400].pixel;
  EXPECT_LE(corner.x(), 639.0);
  EXPECT_LE(corner.y(), 575.0);
}

TEST(InitClicks, SameSeedSameClicksAndAnotherSeedOthers) {
  const TrackInit a = SimulateInitClicks(Frames(), 640, 576, {.seed = 4});
  const TrackInit b = SimulateInitClicks(Frames(), 640, 576, {.seed = 4});
  const TrackInit c = SimulateInitClicks(Frames(), 640, 576, {.seed = 5});
  ASSERT_EQ(a.markers.size(), c.markers.size());
  for (size_t i = 0; i < a.markers.size(); ++i) {
    EXPECT_EQ(a.markers[i].pixel, b.markers[i].pixel);
    EXPECT_NE(a.markers[i].pixel, c.markers[i].pixel);
  }
}

TEST(InitClicks, TheFirstFrameShowingAMarkerIsUsed) {
  std::vector<MarkerFrame2d> frames = Frames();
  for (MarkerBox2d& b : frames[0].markers) b.visible = false;
  const TrackInit init = SimulateInitClicks(frames, 640, 576);
  EXPECT_EQ(init.frame, 1);
  EXPECT_EQ(init.markers.size(), 3u);
}

TEST(InitClicks, WrittenFileReadsBack) {
  const TrackInit init = SimulateInitClicks(Frames(), 640, 576, {.seed = 2});
  const std::filesystem::path path = test::TempDir() / "init.json";
  WriteTrackInitJson(init, path);
  const TrackInit back = ReadTrackInitJson(path);
  EXPECT_EQ(back.frame, init.frame);
  ASSERT_EQ(back.markers.size(), init.markers.size());
  for (size_t i = 0; i < init.markers.size(); ++i) {
    EXPECT_EQ(back.markers[i].id, init.markers[i].id);
    EXPECT_LT((back.markers[i].pixel - init.markers[i].pixel).norm(), 1e-5);
  }
}

TEST(InitClicks, BadInputIsAClearError) {
  std::vector<MarkerFrame2d> frames = Frames();
  for (MarkerFrame2d& f : frames) {
    for (MarkerBox2d& b : f.markers) b.visible = false;
  }
  EXPECT_THAT(test::ErrorOf([&] { SimulateInitClicks(frames, 640, 576); }),
              ::testing::HasSubstr("showing a marker"));
  EXPECT_THAT(test::ErrorOf([&] { SimulateInitClicks(Frames(), 640, 576, {.noise_px = -1}); }),
              ::testing::HasSubstr("noise_px"));
  EXPECT_THAT(test::ErrorOf([&] { SimulateInitClicks(Frames(), 0, 576); }),
              ::testing::HasSubstr("image size"));
}

}  // namespace
}  // namespace simtree::synth
