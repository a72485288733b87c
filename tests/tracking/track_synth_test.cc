// End to end on synth pull streams: synth (the CLI) makes a short capture, Track follows its
// markers from synth's simulated first-frame clicks (pull/init.json), and the scores against the
// truth hold what the tracker reaches today (docs/tracking.md). Issue 20 asks >= 98% tracked, no
// swap and a median 3D error <= 5 mm: on clean colour the first two are met (6.3 mm: guarded at
// 7 mm until the depth is better); on the camera colour synth renders by default the tracker
// reaches 78%, 9.2 mm and 3 swap events (markers 10 and 11; guarded at 75%, 10 mm and 3): the
// saturation cone that removed most swap events on the nine 8 s camera-colour streams
// (docs/tracking.md, "On camera colour") loses this capture 4.5 points and its 0 swaps.
#include <filesystem>

#include <gtest/gtest.h>

#include "simtree/core/progress.h"
#include "simtree/eval/tracking_metrics.h"
#include "simtree/io/ground_truth.h"
#include "simtree/tracking/track.h"
#include "test_util.h"

namespace fs = std::filesystem;

namespace simtree::tracking {
namespace {

struct StreamCase {
  const char* name;
  const char* synth_args;  // beyond species, seed, duration and views
  double min_tracked_fraction;
  double max_median_error_mm;
  int max_swap_events;
};

class TrackSynth : public ::testing::TestWithParam<StreamCase> {};

TEST_P(TrackSynth, ShortStreamTrackedWithoutSwaps) {
  const StreamCase& c = GetParam();
  Progress::SetEnabled(false);
  const fs::path capture = test::TempDir() / "capture";
  const test::CliResult made =
      test::RunCli(std::string("-q synth --species acer_rubrum --seed 2 --duration 5.5 --views 1 "
                               "--no-contact-sheet ") +
                   c.synth_args + " --out " + capture.string());
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const TrackInit init = ReadTrackInitJson(capture / "pull" / "init.json");
  const TrackResult result = Track(capture / "pull", init, TrackOptions{});
  const eval::TrackingScores s = eval::ScoreTracking(
      result.boxes, result.trajectories, ReadMarkers2d(capture / "gt" / "markers_2d.json"),
      ReadTrajectoriesCsv(capture / "gt" / "trajectories.csv"));
  EXPECT_GE(s.tracked_fraction, c.min_tracked_fraction);
  EXPECT_LE(s.median_error_mm, c.max_median_error_mm);
  EXPECT_LE(s.swap_events, c.max_swap_events);
  EXPECT_TRUE(result.never_found.empty());
}

INSTANTIATE_TEST_SUITE_P(Colour, TrackSynth,
                         ::testing::Values(StreamCase{"clean", "--clean-color", 0.98, 7.0, 0},
                                           StreamCase{"camera", "", 0.75, 10.0, 3}),
                         [](const ::testing::TestParamInfo<StreamCase>& p) {
                           return std::string(p.param.name);
                         });

}  // namespace
}  // namespace simtree::tracking
