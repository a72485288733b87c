// The video's options are checked before ffmpeg runs (encoding itself is render_test.cc's).

#include "simtree/viewer/video.h"

#include <gtest/gtest.h>

#include <cmath>

#include "viewer_fixtures.h"

namespace simtree::viewer {
namespace {

TEST(VideoOptions, ValidateNamesTheBadField) {
  EXPECT_NO_THROW(VideoOptions{}.Validate());
  EXPECT_EQ(test::InputErrorField([] { VideoOptions{.fps = 0}.Validate(); }), "fps");
  EXPECT_EQ(test::InputErrorField([] { VideoOptions{.fps = NAN}.Validate(); }), "fps");
  EXPECT_EQ(test::InputErrorField([] { VideoOptions{.crf = 52}.Validate(); }), "crf");
  EXPECT_EQ(test::InputErrorField([] { VideoOptions{.pattern = ""}.Validate(); }), "pattern");
  // Nothing is written for bad options.
  const auto dir = test::TempDir();
  EXPECT_THROW(EncodeVideo(dir, dir / "out.mp4", {.fps = -1}), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "out.mp4"));
}

}  // namespace
}  // namespace simtree::viewer
