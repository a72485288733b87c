// `simtree run` on a small synthetic capture: the whole chain, reuse, redoing from a deleted
// stage, and the same result without the capture's truth.

#include <filesystem>

#include <gtest/gtest.h>

#include "simtree/core/progress.h"
#include "simtree/core/tree_json.h"
#include "simtree/eval/eval_run.h"
#include "simtree/io/trajectories.h"
#include "simtree/pipeline/run.h"
#include "simtree/synth/synth.h"
#include "simtree/tracking/tracker_error.h"
#include "test_util.h"

namespace fs = std::filesystem;
using namespace simtree;

namespace {

const pipeline::StageRecord& Stage(const pipeline::RunResult& r, const std::string& name) {
  for (const auto& s : r.stages) {
    if (s.name == name) return s;
  }
  throw std::runtime_error("no stage " + name);
}

TEST(RunEndToEnd, RunsReusesRedoesAndNeverNeedsTheTruth) {
  Progress::SetEnabled(false);
  const fs::path root = test::TempDir();
  synth::SynthOptions synth;
  synth.quick = true;
  synth.views = 4;
  synth.duration_s = 7.0;
  synth.contact_sheet = false;
  synth::RunSynth(synth, root / "capture");
  // The test, not the run, takes the truth's trajectories (with a tracker's errors) in place of
  // tracking.
  WriteTrajectoriesCsv(tracking::SimulateTrackerError(
                           ReadTrajectoriesCsv(root / "capture" / "gt" / "trajectories.csv"), {}),
                       root / "tracks.csv");
  pipeline::RunOptions options;
  options.tracks = root / "tracks.csv";
  options.render = false;

  const pipeline::RunResult first = pipeline::Run(root / "capture", root / "result", options);
  EXPECT_EQ(first.reused, 0);
  for (const char* name : {"preprocess", "register", "reconstruct", "track", "identify", "build",
                           "simulate", "report"}) {
    EXPECT_EQ(Stage(first, name).status, "done") << name;
  }
  EXPECT_EQ(Stage(first, "render").status, "not run");
  for (const char* file :
       {"register/pull_camera.json", "reconstruct/static.json", "identify/placements.json",
        "build/simready.json", "simulate/nodes.bin", "simulate/markers.csv",
        "simulate/animation.glb", "report.html", "run.json"}) {
    EXPECT_TRUE(fs::exists(root / "result" / file)) << file;
  }

  const pipeline::RunResult second = pipeline::Run(root / "capture", root / "result", options);
  EXPECT_EQ(second.ran, 0);
  EXPECT_EQ(second.reused, 8);

  fs::remove_all(root / "result" / "identify");
  const pipeline::RunResult third = pipeline::Run(root / "capture", root / "result", options);
  EXPECT_TRUE(Stage(third, "reconstruct").reused);
  EXPECT_FALSE(Stage(third, "identify").reused);
  EXPECT_FALSE(Stage(third, "simulate").reused);
  EXPECT_EQ(third.ran, 4);  // identify, build, simulate, report

  // Without gt/: the same simulation-ready tree (up to the registration's floating-point noise
  // across threads: the same branches and markers, nodes within a millimetre).
  fs::copy(root / "capture", root / "bare", fs::copy_options::recursive);
  fs::remove_all(root / "bare" / "gt");
  pipeline::Run(root / "bare", root / "bare_result", options);
  const Tree with_gt = ReadTreeJson(root / "result" / "build" / "simready.json");
  const Tree bare = ReadTreeJson(root / "bare_result" / "build" / "simready.json");
  ASSERT_EQ(bare.size(), with_gt.size());
  for (int b = 0; b < bare.size(); ++b) {
    ASSERT_EQ(bare.branches[b].nodes.size(), with_gt.branches[b].nodes.size()) << b;
    for (size_t n = 0; n < bare.branches[b].nodes.size(); ++n) {
      EXPECT_LT((bare.branches[b].nodes[n].position - with_gt.branches[b].nodes[n].position).norm(),
                1e-3);
    }
    EXPECT_NEAR(bare.branches[b].material->modes[0].frequency_hz,
                with_gt.branches[b].material->modes[0].frequency_hz, 1e-3);
  }
  ASSERT_EQ(bare.markers.size(), with_gt.markers.size());
  for (size_t m = 0; m < bare.markers.size(); ++m) {
    EXPECT_EQ(bare.markers[m].branch, with_gt.markers[m].branch);
  }

  const eval::RunEvaluation ev = eval::EvaluateRun(root / "result", root / "capture");
  EXPECT_TRUE(ev.json["registration"]["scored"].get<bool>());
  EXPECT_TRUE(ev.json["reconstruction"]["scored"].get<bool>());
  EXPECT_TRUE(ev.json["chain"]["scored"].get<bool>());
  EXPECT_FALSE(ev.chain.empty());
  std::printf("%s", ev.markdown.c_str());
}

}  // namespace
