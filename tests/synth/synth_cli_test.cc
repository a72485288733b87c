// `simtree synth` end to end: a quick capture is a capture folder the pipeline opens, its ground
// truth is complete and consistent with the images, the same seed gives the same bytes, and bad
// input gives a clear error and no output.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include <nlohmann/json.hpp>

#include "simtree/core/error.h"
#include "simtree/core/tree_json.h"
#include "simtree/io/capture.h"
#include "simtree/io/ground_truth.h"
#include "simtree/io/track_init.h"
#include "simtree/io/trajectories.h"
#include "simtree/synth/synth.h"
#include "test_util.h"

namespace fs = std::filesystem;

namespace simtree::synth {
namespace {

using ::testing::HasSubstr;

// A quick capture in the test's own folder (CTest runs the tests of a suite side by side).
fs::path QuickCapture(const fs::path& dir, const std::string& extra = "") {
  const test::CliResult r =
      test::RunCli("-q synth --quick --seed 3 " + extra + " --out " + dir.string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return dir;
}

TEST(SynthCli, QuickCaptureIsACaptureFolderWithCompleteGroundTruth) {
  const fs::path dir = QuickCapture(test::TempDir() / "scene");
  const Capture capture = OpenCapture(dir);
  EXPECT_EQ(capture.views.size(), 4u);
  ASSERT_TRUE(capture.pull.has_value());
  EXPECT_EQ(capture.pull->frames.size(), 150u);        // 5 s at 30 fps
  EXPECT_NEAR(capture.pull->FrameRate(), 30.0, 1e-4);  // times have 6 decimals
  EXPECT_TRUE(capture.pull->has_markers);
  EXPECT_TRUE(fs::exists(dir / "contact_sheet.png"));

  // Every view loads: colour and depth of the sensor's size, a fair share of valid depth.
  for (const ScanView& view : capture.views) {
    const RgbdImage image = LoadScanView(view);
    EXPECT_EQ(image.depth.width, 640);
    EXPECT_EQ(image.depth.height, 576);
    int valid = 0;
    for (uint16_t d : image.depth.pixels) valid += d != 0;
    EXPECT_GT(valid, 2000) << view.name;
  }

  const Tree tree = ReadTreeJson(dir / "gt" / "tree.json");
  EXPECT_GE(tree.MaxLevel(), 3);
  EXPECT_FALSE(tree.markers.empty());
  EXPECT_EQ(capture.pull->markers.size(), tree.markers.size());
  EXPECT_EQ(ReadScanPoses(dir / "gt" / "scan_poses.json").size(), capture.views.size());
  const PullLoad load = ReadPullLoad(dir / "gt" / "pull_load.json");
  EXPECT_GT(load.force_n, 0.0);
  EXPECT_LT(load.release_s, 5.0);

  // The true marker tracks: one per marker, every frame; they move while pulled and come back.
  const Trajectories tracks = ReadTrajectoriesCsv(dir / "gt" / "trajectories.csv");
  EXPECT_EQ(tracks.frame_count(), 150);
  ASSERT_EQ(tracks.marker_count(), static_cast<int>(tree.markers.size()));
  const Eigen::Isometry3d camera = ReadPullCamera(dir / "gt" / "pull_camera.json");
  for (const Marker& m : tree.markers) {
    const MarkerTrack* track = tracks.Find(m.id);
    ASSERT_NE(track, nullptr);
    // Frame 0 is the rest pose: the marker's rest position seen from the pull camera.
    EXPECT_LT((track->positions[0] - camera.inverse() * m.position).norm(), 1e-4) << m.id;
  }

  // Boxes: one entry per frame and marker; a visible marker's centre projects into its box.
  const std::vector<MarkerFrame2d> boxes = ReadMarkers2d(dir / "gt" / "markers_2d.json");
  ASSERT_EQ(boxes.size(), 150u);
  const CameraIntrinsics& k = capture.pull->intrinsics;
  int visible = 0;
  for (size_t f = 0; f < boxes.size(); ++f) {
    ASSERT_EQ(boxes[f].markers.size(), tree.markers.size());
    for (size_t m = 0; m < boxes[f].markers.size(); ++m) {
      const MarkerBox2d& b = boxes[f].markers[m];
      if (!b.visible) continue;
      ++visible;
      const Eigen::Vector2d uv = k.Project(tracks.tracks[m].positions[f]);
      EXPECT_GE(uv.x(), b.box[0] - 1.0);
      EXPECT_LE(uv.x(), b.box[0] + b.box[2] + 1.0);
      EXPECT_GE(uv.y(), b.box[1] - 1.0);
      EXPECT_LE(uv.y(), b.box[1] + b.box[3] + 1.0);
    }
  }
  EXPECT_GT(visible, 0);
  // Every tape is seen by the pull camera at rest (placement moves the hidden ones).
  for (const MarkerBox2d& b : boxes[0].markers) EXPECT_TRUE(b.visible) << "marker " << b.id;
  // pull/init.json: a click within a few px of each visible marker's box centre in frame 0.
  const TrackInit init = ReadTrackInitJson(dir / "pull" / "init.json");
  EXPECT_EQ(init.frame, 0);
  ASSERT_EQ(init.markers.size(), boxes[0].markers.size());
  for (size_t m = 0; m < init.markers.size(); ++m) {
    const MarkerBox2d& b = boxes[0].markers[m];
    EXPECT_EQ(init.markers[m].id, b.id);
    const Eigen::Vector2d centre(b.box[0] + 0.5 * b.box[2], b.box[1] + 0.5 * b.box[3]);
    EXPECT_LT((init.markers[m].pixel - centre).norm(), 6.0) << "marker " << b.id;
  }
  // The pull deflects the tied point visibly and stays in the FEM's linear range.
  const nlohmann::json report = nlohmann::json::parse(test::ReadText(dir / "gt" / "synth.json"));
  EXPECT_GT(report.at("pull_deflection_m").get<double>(), 0.05);
  EXPECT_LE(report.at("pull_max_rotation_rad").get<double>(), 0.3 + 1e-9);

  // The modal truth: the tree's modes, a value for every marker link and every branch.
  const ModalTruth truth = ReadModalTruth(dir / "gt" / "modal.json");
  EXPECT_EQ(truth.source, "fem");
  ASSERT_GE(truth.modes.size(), 10u);
  for (size_t i = 1; i < truth.modes.size(); ++i) {
    EXPECT_GE(truth.modes[i].frequency_hz, truth.modes[i - 1].frequency_hz);
  }
  EXPECT_EQ(truth.links.size(), tree.markers.size());  // the root's displacement and each link
  for (const ModalTruth::Link& link : truth.links) {
    EXPECT_GT(link.frequency_hz, 0.0);
    EXPECT_GT(link.damping_ratio, 0.0);
  }
  EXPECT_FALSE(truth.branches.empty());
}

TEST(SynthCli, SameSeedSameBytes) {
  const fs::path dir = test::TempDir();
  const fs::path first = QuickCapture(dir / "first");
  const fs::path again = QuickCapture(dir / "again", "--threads 1 --no-contact-sheet");
  for (const char* file :
       {"scans/view_02/depth.png", "scans/view_02/color.png", "pull/depth/000100.png",
        "pull/color/000100.png", "gt/tree.json", "gt/trajectories.csv", "gt/modal.json",
        "gt/markers_2d.json", "pull/init.json"}) {
    EXPECT_EQ(test::ReadText(first / file), test::ReadText(again / file)) << file;
  }
}

// --truth-only stops after the FEM oracle: gt/ only, and the same modal truth as the whole run.
TEST(SynthCli, TruthOnlyWritesTheSameTruthWithoutImages) {
  const fs::path dir = test::TempDir();
  const fs::path whole = QuickCapture(dir / "whole", "--no-contact-sheet");
  const fs::path truth = QuickCapture(dir / "truth", "--truth-only");
  for (const char* file : {"gt/tree.json", "gt/modal.json", "gt/pull_load.json"}) {
    EXPECT_EQ(test::ReadText(whole / file), test::ReadText(truth / file)) << file;
  }
  EXPECT_FALSE(fs::exists(truth / "scans"));
  EXPECT_FALSE(fs::exists(truth / "pull"));
  EXPECT_FALSE(fs::exists(truth / "gt" / "trajectories.csv"));
}

TEST(SynthCli, BadInputGivesAClearErrorAndNoOutput) {
  const fs::path dir = test::TempDir();
  test::CliResult r = test::RunCli("synth --species oak --out " + (dir / "a").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("oak"));
  EXPECT_FALSE(fs::exists(dir / "a"));

  test::WriteText(dir / "species.json", "{\"base\": \"magnolia\", \"height_m\": -3}");
  r = test::RunCli("synth --species-file " + (dir / "species.json").string() + " --out " +
                   (dir / "b").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("height_m"));
  EXPECT_FALSE(fs::exists(dir / "b"));

  test::WriteText(dir / "truncated.json", "{\"base\": \"magnolia\", \"height_m\": ");
  r = test::RunCli("synth --species-file " + (dir / "truncated.json").string() + " --out " +
                   (dir / "c").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("truncated.json"));
  EXPECT_FALSE(fs::exists(dir / "c"));

  r = test::RunCli("synth --quick --out " + dir.string() + " --species-file " +
                   (dir / "species.json").string());
  EXPECT_NE(r.exit_code, 0);  // the output folder holds an input
  EXPECT_TRUE(fs::exists(dir / "species.json"));

  r = test::RunCli("synth --quick");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("--out"));
}

// Where the rope is tied moves the rope and nothing else: the same tree and markers (so the same
// static scans), the rope at that share of the same branch, a different pull.
TEST(SynthCli, PullPositionMovesOnlyTheRope) {
  const fs::path dir = test::TempDir();
  const fs::path near = QuickCapture(dir / "near", "--truth-only");
  const fs::path far = QuickCapture(dir / "far", "--truth-only --pull-position 0.65");
  EXPECT_EQ(test::ReadText(near / "gt" / "tree.json"), test::ReadText(far / "gt" / "tree.json"));
  const Tree tree = ReadTreeJson(near / "gt" / "tree.json");
  const PullLoad near_load = ReadPullLoad(near / "gt" / "pull_load.json");
  const PullLoad far_load = ReadPullLoad(far / "gt" / "pull_load.json");
  ASSERT_EQ(near_load.branch, far_load.branch);
  const double length = tree.branches.at(near_load.branch).Length();
  EXPECT_NEAR(near_load.arc_length, 0.35 * length, 1e-9);
  EXPECT_NEAR(far_load.arc_length, 0.65 * length, 1e-9);
  // Nearer the crotch the branch is stiffer: the same swing takes more force.
  EXPECT_GT(near_load.force_n, far_load.force_n);
}

TEST(SynthCli, PullOptionsOutOfRangeAreRefusedBeforeAnythingIsWritten) {
  const fs::path dir = test::TempDir() / "never";
  for (const auto& change : std::vector<std::function<void(SynthOptions&)>>{
           [](SynthOptions& o) { o.pull_deflection_m = -0.1; },
           [](SynthOptions& o) { o.pull_deflection_m = std::nan(""); },
           [](SynthOptions& o) { o.pull_deflection_per_length = 0.0; },
           [](SynthOptions& o) { o.pull_deflection_per_length = 0.9; },
           [](SynthOptions& o) { o.pull_position = 0.0; },
           [](SynthOptions& o) { o.pull_position = 1.0; },
           [](SynthOptions& o) { o.pull_position = std::nan(""); },
           [](SynthOptions& o) { o.max_pull_rotation_rad = 0.0; },
           [](SynthOptions& o) { o.max_pull_rotation_rad = 1.0; },
           [](SynthOptions& o) { o.init_click_noise_px = -1.0; },
           [](SynthOptions& o) { o.color_width = 1280; },
           [](SynthOptions& o) {
             o.color_width = 1280;
             o.color_height = 721;
           }}) {
    SynthOptions options;
    options.quick = true;
    change(options);
    EXPECT_THROW(RunSynth(options, dir), InputError);
    EXPECT_FALSE(fs::exists(dir));
  }
}

// --hard: leaves hide markers for a while (visible false in some frames, never all of them), but
// not in the first frame, so init.json holds every marker; clean colour differs from the
// camera's only in colour.
TEST(SynthCli, HardStreamHidesMarkersBehindLeavesForAWhile) {
  const fs::path tmp = test::TempDir();  // emptied on every call: once
  const fs::path dir = QuickCapture(tmp / "hard", "--hard --no-contact-sheet");
  const std::vector<MarkerFrame2d> boxes = ReadMarkers2d(dir / "gt" / "markers_2d.json");
  ASSERT_FALSE(boxes.empty());
  int hidden_for_a_while = 0;
  for (size_t m = 0; m < boxes[0].markers.size(); ++m) {
    int visible = 0;
    for (const MarkerFrame2d& f : boxes) visible += f.markers[m].visible;
    hidden_for_a_while += visible > 0 && visible < static_cast<int>(boxes.size()) - 5;
  }
  EXPECT_GE(hidden_for_a_while, 1);
  EXPECT_EQ(ReadTrackInitJson(dir / "pull" / "init.json").markers.size(), boxes[0].markers.size());
  const fs::path clean =
      QuickCapture(tmp / "hard_clean", "--hard --clean-color --no-contact-sheet");
  EXPECT_EQ(test::ReadText(dir / "pull/depth/000100.png"),
            test::ReadText(clean / "pull/depth/000100.png"));
  EXPECT_EQ(test::ReadText(dir / "gt/markers_2d.json"),
            test::ReadText(clean / "gt/markers_2d.json"));
  EXPECT_NE(test::ReadText(dir / "pull/color/000100.png"),
            test::ReadText(clean / "pull/color/000100.png"));
}

// --color-size 1280x720: the pull stream is the colour camera's throughout (intrinsics, colour,
// depth registered into it, marker boxes, clicks, true tracks and pose), the scans stay as they
// are; a size the camera does not have is refused before anything is written.
TEST(SynthCli, ColorSizeMakesTheStreamTheColourCamerasThroughout) {
  const fs::path tmp = test::TempDir();
  for (const char* bad : {"1280x721", "1280", "big"}) {
    const test::CliResult r = test::RunCli(std::string("synth --quick --color-size ") + bad +
                                           " --out " + (tmp / "bad").string());
    EXPECT_NE(r.exit_code, 0) << bad;
    EXPECT_THAT(r.output, HasSubstr("color")) << bad;
    EXPECT_THAT(r.output, HasSubstr(bad));
    EXPECT_THAT(r.output, HasSubstr("1280x720")) << bad;  // what it takes
    EXPECT_FALSE(fs::exists(tmp / "bad"));
  }
  const fs::path dir =
      QuickCapture(tmp / "hd", "--duration 2 --views 1 --no-contact-sheet --color-size 1280x720");
  const Capture capture = OpenCapture(dir);
  ASSERT_TRUE(capture.pull.has_value());
  const CameraIntrinsics& k = capture.pull->intrinsics;
  EXPECT_EQ(k.width, 1280);
  EXPECT_EQ(k.height, 720);
  EXPECT_EQ(LoadScanView(capture.views.at(0)).depth.width, 640);
  const RgbdImage first = LoadPullFrame(*capture.pull, 0);
  ASSERT_EQ(first.depth.width, 1280);
  ASSERT_EQ(first.color.width, 1280);

  const Tree tree = ReadTreeJson(dir / "gt" / "tree.json");
  const Trajectories tracks = ReadTrajectoriesCsv(dir / "gt" / "trajectories.csv");
  const Eigen::Isometry3d camera = ReadPullCamera(dir / "gt" / "pull_camera.json");
  const std::vector<MarkerFrame2d> boxes = ReadMarkers2d(dir / "gt" / "markers_2d.json");
  const TrackInit init = ReadTrackInitJson(dir / "pull" / "init.json");
  ASSERT_EQ(init.markers.size(), tree.markers.size());
  int agree = 0;
  for (size_t m = 0; m < tree.markers.size(); ++m) {
    const Eigen::Vector3d centre = tracks.tracks[m].positions[0];
    EXPECT_LT((centre - camera.inverse() * tree.markers[m].position).norm(), 1e-4);
    const MarkerBox2d& b = boxes[0].markers[m];
    ASSERT_TRUE(b.visible) << "marker " << b.id;
    const Eigen::Vector2d uv = k.Project(centre);
    EXPECT_GE(uv.x(), b.box[0] - 1.0);
    EXPECT_LE(uv.x(), b.box[0] + b.box[2] + 1.0);
    EXPECT_GE(uv.y(), b.box[1] - 1.0);
    EXPECT_LE(uv.y(), b.box[1] + b.box[3] + 1.0);
    EXPECT_LT((init.markers[m].pixel - uv).norm(), 8.0) << "marker " << b.id;
    // The registered depth on the tape is the marker's depth in this camera (its surface, a
    // branch radius nearer, plus the sensor's noise).
    double nearest = 1e9;
    for (int y = std::max(0, static_cast<int>(uv.y()) - 2); y <= static_cast<int>(uv.y()) + 2;
         ++y) {
      for (int x = std::max(0, static_cast<int>(uv.x()) - 2); x <= static_cast<int>(uv.x()) + 2;
           ++x) {
        if (x >= k.width || y >= k.height || first.depth.at(x, y) == 0) continue;
        nearest = std::min(nearest, std::abs(0.001 * first.depth.at(x, y) - centre.z()));
      }
    }
    agree += nearest < 0.05;
  }
  EXPECT_GE(agree, static_cast<int>(tree.markers.size()) * 3 / 4);
}

TEST(SynthCli, HelpTeachesAndListsSpecies) {
  test::CliResult r = test::RunCli("synth --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("--species"));
  EXPECT_THAT(r.output, HasSubstr("--quick"));
  EXPECT_THAT(r.output, HasSubstr("--hard"));
  EXPECT_THAT(r.output, HasSubstr("simtree synth --species acer_rubrum --seed 7 --out scene/"));
  r = test::RunCli("synth --list-species");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* name : {"acer_palmatum", "magnolia", "acer_rubrum"}) {
    EXPECT_THAT(r.output, HasSubstr(name));
  }
}

}  // namespace
}  // namespace simtree::synth
