#include "simtree/tracking/track.h"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "drawn_stream.h"
#include "simtree/core/error.h"
#include "simtree/core/progress.h"
#include "simtree/tracking/boxes_file.h"
#include "test_util.h"

namespace fs = std::filesystem;

namespace simtree::tracking {
namespace {

// Two markers swinging in opposite phase so they cross in the image, one 0.4 m behind the other,
// and a third one still.
test::DrawnStream CrossingStream(int frames) {
  test::DrawnStream s;
  for (int f = 0; f < frames; ++f) {
    const double t = f / s.fps;
    const double swing = 0.12 * std::sin(2 * M_PI * 0.8 * t);
    s.positions.push_back({Eigen::Vector3d(swing, 0.0, 1.5),
                           Eigen::Vector3d(-swing * 1.2, 0.01, 1.9),
                           Eigen::Vector3d(0.2, -0.2, 1.7)});
  }
  return s;
}

class TrackTest : public ::testing::Test {
 protected:
  void SetUp() override { Progress::SetEnabled(false); }
};

TEST_F(TrackTest, FollowsCrossingMarkersWithoutSwapsOrInventedPositions) {
  test::DrawnStream s = CrossingStream(60);
  for (int f = 20; f < 24; ++f) s.positions[f][2].z() = -1.0;  // hidden: not drawn
  const fs::path pull = test::TempDir() / "pull";
  const TrackInit init = test::WriteDrawnStream(s, pull);
  const TrackResult r = Track(pull, init, TrackOptions{});
  ASSERT_EQ(r.trajectories.frame_count(), 60);
  ASSERT_EQ(r.trajectories.marker_count(), 3);
  int measured = 0, expected = 0;
  for (int f = 0; f < 60; ++f) {
    for (int m = 0; m < 3; ++m) {
      const bool hidden = s.positions[f][m].z() < 0;
      const MarkerTrack& track = r.trajectories.tracks[m];
      if (hidden) {
        EXPECT_FALSE(track.valid[f]) << "frame " << f << ": a hidden marker got a position";
        EXPECT_NE(r.boxes[f].markers[m].state, MarkerState::kTracked);
        continue;
      }
      ++expected;
      if (!track.valid[f]) continue;
      ++measured;
      // Right identity and within a few millimetres (crossing frames included).
      EXPECT_LT((track.positions[f] - s.positions[f][m]).norm(), 0.006)
          << "frame " << f << " marker " << m;
    }
  }
  EXPECT_GE(measured, expected * 0.95);
  EXPECT_EQ(r.boxes[21].markers[2].state, MarkerState::kPredicted);
  EXPECT_EQ(r.boxes[30].markers[2].state, MarkerState::kTracked);
  EXPECT_TRUE(r.never_found.empty());
}

TEST_F(TrackTest, WritesOutputsThatReadBack) {
  const test::DrawnStream s = CrossingStream(8);
  const fs::path dir = test::TempDir();
  const TrackInit init = test::WriteDrawnStream(s, dir / "pull");
  const TrackResult r = Track(dir / "pull", init, TrackOptions{});
  WriteTrackOutputs(r, dir / "tracks", TrackOutputOptions{.overlay = true});
  const Trajectories back = ReadTrajectoriesCsv(dir / "tracks" / "trajectories.csv");
  EXPECT_EQ(back.frame_count(), 8);
  const std::vector<FrameBoxes> boxes = ReadBoxesCsv(dir / "tracks" / "boxes.csv");
  ASSERT_EQ(boxes.size(), 8u);
  EXPECT_NEAR(boxes[3].markers[1].box[2], r.boxes[3].markers[1].box[2], 1e-3);
  EXPECT_TRUE(fs::exists(dir / "tracks" / "markers.json"));
  EXPECT_TRUE(fs::exists(dir / "tracks" / "track_summary.json"));
  EXPECT_TRUE(fs::exists(dir / "tracks" / "overlay" / "000007.png"));
}

TEST_F(TrackTest, RefusesAnInitMarkerThatMarkersJsonLacks) {
  const fs::path pull = test::TempDir() / "pull";
  TrackInit init = test::WriteDrawnStream(CrossingStream(3), pull);
  init.markers.push_back({7, Eigen::Vector2d(10, 10)});
  try {
    Track(pull, init, TrackOptions{});
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("marker 7 is not in"), std::string::npos) << e.what();
  }
}

TEST_F(TrackTest, RefusesAMissingFrameFile) {
  const fs::path pull = test::TempDir() / "pull";
  const TrackInit init = test::WriteDrawnStream(CrossingStream(3), pull);
  fs::remove(pull / "depth" / "000002.png");
  EXPECT_THROW(Track(pull, init, TrackOptions{}), InputError);
}

TEST_F(TrackTest, RefusesDepthOfTheWrongSize) {
  const fs::path pull = test::TempDir() / "pull";
  const TrackInit init = test::WriteDrawnStream(CrossingStream(3), pull);
  WritePng(DepthImage(10, 10, 1000), pull / "depth" / "000001.png");
  try {
    Track(pull, init, TrackOptions{});
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("000001.png"), std::string::npos) << e.what();
  }
}

TEST_F(TrackTest, RefusesAnUnreadablePng) {
  const fs::path pull = test::TempDir() / "pull";
  const TrackInit init = test::WriteDrawnStream(CrossingStream(3), pull);
  test::WriteText(pull / "color" / "000002.png", "not a png");
  EXPECT_THROW(Track(pull, init, TrackOptions{}), Error);
}

TEST_F(TrackTest, FlagsAFrameWithNoMarkerColour) {
  test::DrawnStream s = CrossingStream(6);
  for (auto& p : s.positions[3]) p.z() = -1.0;  // nothing drawn in frame 3
  const fs::path pull = test::TempDir() / "pull";
  const TrackInit init = test::WriteDrawnStream(s, pull);
  const TrackResult r = Track(pull, init, TrackOptions{});
  ASSERT_EQ(r.flagged.size(), 1u);
  EXPECT_EQ(r.flagged[0].frame, 3);
  for (const MarkerTrack& t : r.trajectories.tracks) EXPECT_FALSE(t.valid[3]);
}

TEST_F(TrackTest, RefusesAnInitWithNoTapeColourAtAll) {
  const fs::path pull = test::TempDir() / "pull";
  TrackInit init = test::WriteDrawnStream(CrossingStream(3), pull);
  for (MarkerPixel& m : init.markers) m.pixel = Eigen::Vector2d(5, 5);  // a corner: background
  EXPECT_THROW(Track(pull, init, TrackOptions{}), InputError);
}

TEST_F(TrackTest, AMarkerThatNeverAppearsIsReportedAndNeverInvented) {
  const fs::path pull = test::TempDir() / "pull";
  TrackInit init = test::WriteDrawnStream(CrossingStream(5), pull);
  init.markers[2].pixel = Eigen::Vector2d(300, 20);  // nothing there, ever
  const TrackResult r = Track(pull, init, TrackOptions{});
  ASSERT_EQ(r.never_found, std::vector<int>{2});
  EXPECT_EQ(r.trajectories.tracks[2].valid_count(), 0);
  EXPECT_EQ(r.counts[2].lost, 5);
  EXPECT_EQ(r.trajectories.tracks[0].valid_count(), 5);
}

TEST_F(TrackTest, AMarkerNotYetFoundNeverTakesATrackedNeighboursTape) {
  // Marker 1's tape never shows; its click lies 10 px from marker 0. In frame 5 marker 0's depth
  // jumps 0.25 m (a mixed depth), so marker 0 cannot take its own blob: marker 1 must not either.
  test::DrawnStream s;
  for (int f = 0; f < 10; ++f) {
    const double z = f == 5 ? 1.75 : 1.5;
    s.positions.push_back({Eigen::Vector3d(0.0, 0.0, z), Eigen::Vector3d(0, 0, -1.0)});
  }
  const fs::path pull = test::TempDir() / "pull";
  TrackInit init = test::WriteDrawnStream(s, pull);
  init.markers[1].pixel = init.markers[0].pixel + Eigen::Vector2d(10.0, 0.0);
  const TrackResult r = Track(pull, init, TrackOptions{});
  EXPECT_EQ(r.trajectories.tracks[1].valid_count(), 0);
  EXPECT_EQ(r.trajectories.tracks[0].valid_count(), 9);
}

TEST_F(TrackTest, ACoastingMarkersPredictionSlowsDown) {
  // Marker 0 moves 0.3 m/s across the image, hides for 8 frames and shows again where it hid
  // (a swing turning back): its prediction must not run on at full speed.
  test::DrawnStream s;
  for (int f = 0; f < 34; ++f) {
    const double x = 0.01 * std::min(f, 19);
    s.positions.push_back({Eigen::Vector3d(x, 0.0, 1.5)});
    if (f >= 20 && f < 28) s.positions.back()[0].z() = -1.0;
  }
  const fs::path pull = test::TempDir() / "pull";
  const TrackInit init = test::WriteDrawnStream(s, pull);
  const TrackResult r = Track(pull, init, TrackOptions{});
  const Eigen::Vector2d hid = s.intrinsics.Project(s.positions[19][0]);
  const auto& coast = r.boxes[27].markers[0];
  EXPECT_EQ(coast.state, MarkerState::kPredicted);
  EXPECT_LT((Eigen::Vector2d(coast.center[0], coast.center[1]) - hid).norm(), 5.0);
  EXPECT_TRUE(r.trajectories.tracks[0].valid[30]);
}

TEST_F(TrackTest, AFewTapeColouredPixelsWithoutDepthAreNotTheMarker) {
  // From frame 10 marker 0's tape is gone; 2 x 2 pixels of its colour without depth (camera
  // noise) lie 3 px beside where it was.
  test::DrawnStream s;
  for (int f = 0; f < 16; ++f) {
    s.positions.push_back({Eigen::Vector3d(0.0, 0.0, f < 10 ? 1.5 : -1.0)});
  }
  const fs::path pull = test::TempDir() / "pull";
  const TrackInit init = test::WriteDrawnStream(s, pull);
  const Eigen::Vector2d at = init.markers[0].pixel;
  for (int f = 10; f < 16; ++f) {
    RgbdImage image = test::DrawFrame(s, s.positions[f]);
    for (int y = 0; y < 2; ++y) {
      for (int x = 0; x < 2; ++x) {
        const int px = static_cast<int>(at.x()) + 3 + x, py = static_cast<int>(at.y()) + y;
        for (int ch = 0; ch < 3; ++ch) image.color.at(px, py, ch) = s.tape[ch];
        image.depth.at(px, py) = 0;
      }
    }
    WritePullFrame(pull, f, f / s.fps, image.color, image.depth);
  }
  const TrackResult r = Track(pull, init, TrackOptions{});
  for (int f = 10; f < 16; ++f) {
    EXPECT_NE(r.boxes[f].markers[0].state, MarkerState::kTracked) << "frame " << f;
  }
}

TEST_F(TrackTest, OptionsOutOfRangeNameTheField) {
  TrackOptions o;
  o.gate_mm = -1;
  try {
    o.Validate();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("gate_mm"), std::string::npos);
  }
  o = TrackOptions{};
  o.color = "mauve";
  EXPECT_THROW(o.Validate(), InputError);
}

}  // namespace
}  // namespace simtree::tracking

namespace simtree::tracking {
namespace {

TEST(TrackCli, WritesOutputsAndRefusesAMissingInit) {
  const fs::path dir = test::TempDir();
  const TrackInit init = test::WriteDrawnStream(CrossingStream(4), dir / "pull");
  const std::string pull = (dir / "pull").string(), out = (dir / "t").string();
  const test::CliResult missing = test::RunCli(fmt::format("-q track {} --out {}", pull, out));
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.output.find("init.json"), std::string::npos) << missing.output;
  WriteTrackInitJson(init, dir / "init.json");
  const test::CliResult ok = test::RunCli(
      fmt::format("-q track {} --init {} --out {}", pull, (dir / "init.json").string(), out));
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_TRUE(fs::exists(dir / "t" / "trajectories.csv"));
  EXPECT_TRUE(fs::exists(dir / "t" / "boxes.csv"));
}

}  // namespace
}  // namespace simtree::tracking
