#include "simtree/io/trajectories.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "test_util.h"

namespace simtree {
namespace {

using ::testing::HasSubstr;

Trajectories TwoMarkers() {
  Trajectories t;
  t.tracks = {MarkerTrack{0, {}, {}}, MarkerTrack{3, {}, {}}};
  for (int f = 0; f < 5; ++f) {
    const double time = f / 30.0;
    t.AddFrame(f, time, {Eigen::Vector3d(0.1 * f, -0.2, 1.5), Eigen::Vector3d(0.3, 0.01 * f, 2.0)},
               {true, f != 2});
  }
  return t;
}

std::string Header() {
  return std::string(kTrajectoriesFirstLine) + "\n" + kTrajectoriesHeader + "\n";
}

TEST(Trajectories, RoundTripKeepsPositionsToTheMicrometreAndGaps) {
  const Trajectories t = TwoMarkers();
  const std::string csv = TrajectoriesToCsv(t);
  EXPECT_THAT(csv, HasSubstr("2,0.066667,3,,,,0\n"));
  const Trajectories back = ParseTrajectoriesCsv(csv, "t.csv");
  ASSERT_EQ(back.frame_count(), 5);
  ASSERT_EQ(back.marker_count(), 2);
  EXPECT_EQ(back.tracks[1].marker, 3);
  EXPECT_EQ(back.tracks[1].valid_count(), 4);
  EXPECT_FALSE(back.tracks[1].valid[2]);
  EXPECT_TRUE(std::isnan(back.tracks[1].positions[2].x()));
  for (int f = 0; f < 5; ++f) {
    EXPECT_NEAR(back.times_s[f], f / 30.0, 1e-6);
    EXPECT_LT((back.tracks[0].positions[f] - t.tracks[0].positions[f]).norm(), 1e-6);
  }
  // Writing what was read gives the same bytes.
  EXPECT_EQ(TrajectoriesToCsv(back), csv);
}

TEST(Trajectories, FileRoundTripAndMarkerOrderWithinAFrameIsFree) {
  const auto dir = test::TempDir();
  WriteTrajectoriesCsv(TwoMarkers(), dir / "t.csv");
  EXPECT_EQ(ReadTrajectoriesCsv(dir / "t.csv").frame_count(), 5);
  const std::string swapped = Header() +
                              "0,0.0,1,0,0,1,1\n0,0.0,2,0,0,2,1\n"
                              "1,0.1,2,nan,nan,nan,0\n1,0.1,1,0,0,1.5,1\n";
  const Trajectories t = ParseTrajectoriesCsv(swapped, "s.csv");
  EXPECT_DOUBLE_EQ(t.Find(1)->positions[1].z(), 1.5);
  EXPECT_FALSE(t.Find(2)->valid[1]);
}

struct BadCsv {
  const char* name;
  std::string text;
  const char* expected;
};

TEST(Trajectories, BadFilesSayWhereAndWhat) {
  const std::vector<BadCsv> cases = {
      {"empty", "", "the file is empty"},
      {"wrong first line", "frame,time_s\n", "expected the first line"},
      {"no header", std::string(kTrajectoriesFirstLine) + "\n", "expected the header"},
      {"no frames", Header(), "at least one frame"},
      {"few fields", Header() + "0,0,1,0,0\n", "line 3: expected 7 fields"},
      {"valid nan", Header() + "0,0,1,nan,0,0,1\n", "a valid row needs a finite"},
      {"bad valid", Header() + "0,0,1,0,0,0,2\n", "valid: expected 0 or 1"},
      {"text coordinate", Header() + "0,0,1,abc,0,0,1\n", "x: expected a number"},
      {"missing marker", Header() + "0,0,1,0,0,0,1\n0,0,2,0,0,0,1\n1,0.1,1,0,0,0,1\n",
       "marker 2 is missing"},
      {"late marker", Header() + "0,0,1,0,0,0,1\n1,0.1,1,0,0,0,1\n1,0.1,2,0,0,0,1\n",
       "first appears in frame 1"},
      {"twice", Header() + "0,0,1,0,0,0,1\n0,0,1,0,0,0,1\n", "appears twice"},
      {"time back", Header() + "0,0.2,1,0,0,0,1\n1,0.1,1,0,0,0,1\n", "is not after"},
      {"frame back", Header() + "3,0.2,1,0,0,0,1\n1,0.3,1,0,0,0,1\n", "increasing order"},
      {"time per frame", Header() + "0,0,1,0,0,0,1\n0,0.1,2,0,0,0,1\n", "on the same frame"},
  };
  for (const BadCsv& c : cases) {
    try {
      ParseTrajectoriesCsv(c.text, "bad.csv");
      ADD_FAILURE() << c.name << ": no error";
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr("bad.csv")) << c.name;
      EXPECT_THAT(e.what(), HasSubstr(c.expected)) << c.name;
    }
  }
}

TEST(Trajectories, WriterRefusesWhatTheReaderWouldRefuse) {
  Trajectories t = TwoMarkers();
  t.tracks[0].positions[1].x() = std::nan("");
  EXPECT_THROW(TrajectoriesToCsv(t), InputError);
  t = TwoMarkers();
  t.times_s[3] = t.times_s[2];
  EXPECT_THROW(TrajectoriesToCsv(t), InputError);
  EXPECT_THROW(TrajectoriesToCsv(Trajectories{}), InputError);
  t = TwoMarkers();
  EXPECT_THROW(t.AddFrame(9, 1.0, {Eigen::Vector3d::Zero()}, {true}), InputError);
}

}  // namespace
}  // namespace simtree
