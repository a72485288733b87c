#include "simtree/io/track_init.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "test_util.h"

namespace simtree {
namespace {

using ::testing::HasSubstr;

// The message of the InputError that reading `text` as init.json throws ("" when none).
std::string ReadError(const std::string& text) {
  const auto path = test::TempDir() / "init.json";
  test::WriteText(path, text);
  try {
    ReadTrackInitJson(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(TrackInit, RoundTripKeepsIdsFrameAndPixels) {
  TrackInit init;
  init.frame = 3;
  init.markers = {{4, Eigen::Vector2d(312.4, 401.25)}, {0, Eigen::Vector2d(0.0, 17.123456789)}};
  const auto path = test::TempDir() / "init.json";
  WriteTrackInitJson(init, path);
  const TrackInit back = ReadTrackInitJson(path);
  EXPECT_EQ(back.frame, 3);
  ASSERT_EQ(back.markers.size(), 2u);
  EXPECT_EQ(back.markers[0].id, 4);
  EXPECT_DOUBLE_EQ(back.markers[0].pixel.x(), 312.4);
  EXPECT_EQ(back.markers[1].id, 0);
  EXPECT_NEAR(back.markers[1].pixel.y(), 17.123457, 1e-9);
}

TEST(TrackInit, BadFilesNameTheFieldAndWhatWasExpected) {
  const std::string head = R"({"format": "simtree.track_init", "version": 1, "frame": 0, )";
  EXPECT_THAT(ReadError(head + R"("markers": []})"), HasSubstr("markers: expected at least one"));
  EXPECT_THAT(
      ReadError(head + R"("markers": [{"id": 1, "pixel": [1, 2]}, {"id": 1, "pixel": [3, 4]}]})"),
      HasSubstr("markers[1].id: marker id 1 appears twice"));
  EXPECT_THAT(ReadError(head + R"("markers": [{"id": 1, "pixel": [1]}]})"),
              HasSubstr("markers[0].pixel: expected 2 numbers"));
  EXPECT_THAT(ReadError(head + R"("markers": [{"id": 1, "pixel": [-4, 2]}]})"),
              HasSubstr("markers[0].pixel: expected a pixel inside the image"));
  EXPECT_THAT(ReadError(head + R"("markers": [{"id": -2, "pixel": [4, 2]}]})"),
              HasSubstr("markers[0].id: expected an id >= 0"));
  EXPECT_THAT(
      ReadError(R"({"format": "simtree.markers", "version": 1, "frame": 0, "markers": []})"),
      HasSubstr("simtree.track_init"));
  EXPECT_THAT(ReadError(head), HasSubstr("init.json"));  // truncated
  EXPECT_FALSE(ReadError(head + R"("markers": [{"id": 1, "pixel": [4, 2]}]})").size());
}

TEST(TrackInit, MissingFileSaysWhatWritesOne) {
  try {
    ReadTrackInitJson(test::TempDir() / "absent.json");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("simtree track --pick"));
  }
}

}  // namespace
}  // namespace simtree
