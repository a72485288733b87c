// The stage table: what each stage reads, writes and depends on.

#include "simtree/pipeline/detail/stage_functions.h"
#include "simtree/pipeline/manifest.h"
#include "simtree/pipeline/run.h"
#include "simtree/pipeline/stage.h"

namespace simtree::pipeline {
namespace {

using ojson = nlohmann::ordered_json;

ojson SeedOnly(const RunOptions& o) { return {{"seed", o.seed}}; }
ojson NoOptions(const RunOptions&) { return ojson::object(); }

ojson TrackOptions(const RunOptions& o) {
  if (o.tracks.empty()) return {{"tracks", nullptr}};
  return {{"tracks", o.tracks.string()}, {"tracks_fingerprint", FingerprintPaths({o.tracks})}};
}

std::vector<Stage> MakeTable() {
  using namespace detail;
  return {
      {"preprocess", {"capture/scans"}, {"preprocess"}, SeedOnly, RunPreprocessStage},
      {"register",
       {"preprocess", "capture/pull/intrinsics.json", "capture/pull/frames.csv"},
       {"register"},
       SeedOnly,
       RunRegisterStage},
      {"reconstruct", {"register/merged.ply"}, {"reconstruct"}, SeedOnly, RunReconstructStage},
      {"track", {"capture/pull"}, {"track"}, TrackOptions, RunTrackStage},
      {"identify",
       {"track/trajectories.csv", "capture/pull/markers.json", "register/pull_camera.json",
        "reconstruct/static.json"},
       {"identify"},
       [](const RunOptions& o) {
         return ojson{{"held_out_markers", o.held_out_markers}};
       },
       RunIdentifyStage},
      {"build",
       {"reconstruct/static.json", "identify", "track/trajectories.csv",
        "register/pull_camera.json"},
       {"build"},
       NoOptions,
       RunBuildStage},
      {"simulate",
       {"build/simready.json", "track/trajectories.csv", "identify", "register/pull_camera.json"},
       {"simulate"},
       NoOptions,
       RunSimulateStage},
      {"render",
       {"build/simready.json", "simulate/simulation.json", "register/pull_camera.json",
        "capture/pull"},
       {"render"},
       [](const RunOptions& o) {
         return ojson{{"render_width", o.render_width}};
       },
       RunRenderStage},
      {"report",
       {"preprocess", "register", "reconstruct", "track", "identify", "build", "simulate", "render",
        "eval"},
       {"report.html"},
       NoOptions,
       RunReportStage,
       /*folder=*/false},
  };
}

}  // namespace

const std::vector<Stage>& StageTable() {
  static const std::vector<Stage> table = MakeTable();
  return table;
}

const std::vector<std::string>& StageNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const Stage& s : StageTable()) out.push_back(s.name);
    return out;
  }();
  return names;
}

}  // namespace simtree::pipeline
