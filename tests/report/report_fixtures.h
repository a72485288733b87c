#pragma once
// A small result folder made at test time, as `simtree run` would leave it: a hand-made
// three-level tree pulled and released by the dynamics library (nodes.bin, markers), its markers'
// trajectories identified by the identification library (materials.json), small pictures in
// place of the stages' images, and hand-written run.json, poses, pairs and eval.json.

#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "dynamics/dynamics_fixtures.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/tree_json.h"
#include "simtree/dynamics/recorders.h"
#include "simtree/dynamics/simulate.h"
#include "simtree/identification/identify.h"
#include "simtree/identification/materials_file.h"
#include "simtree/io/image_io.h"
#include "simtree/io/trajectories.h"

namespace simtree::test {

// A picture of `width` x `height` whose colours depend on `seed` (so frames differ).
inline RgbImage TestPicture(int width, int height, int seed) {
  RgbImage image(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      image.at(x, y, 0) = static_cast<uint8_t>((x * 255) / width);
      image.at(x, y, 1) = static_cast<uint8_t>((y * 255) / height);
      image.at(x, y, 2) = static_cast<uint8_t>((seed * 37) % 256);
    }
  }
  return image;
}

inline void WriteJson(const std::filesystem::path& path, const nlohmann::json& doc) {
  std::filesystem::create_directories(path.parent_path());
  WriteFileAtomically(path, doc.dump(1));
}

// simulate/ (nodes.bin, markers, simulation.json), build/simready.json and track/ from one pull of
// ThreeLevelTree; identify/materials.json from the markers' tracks.
inline void WriteSimulatedStages(const std::filesystem::path& root, double duration_s = 4.0) {
  namespace fs = std::filesystem;
  const Tree tree = ThreeLevelTree();
  dynamics::SimulationOptions options;
  options.duration_s = duration_s;
  options.fps = 30;
  dynamics::PullSchedule pull;
  pull.rope.branch = 1;
  pull.rope.anchor = tree.branches[1].tip().position + Eigen::Vector3d(0, -0.5, -2.0);
  pull.rope.force_n = 150;
  pull.hold_s = 0.5;
  pull.release_s = 1.0;
  options.pull = pull;
  for (const char* d : {"simulate", "build", "track", "identify", "reconstruct"}) {
    fs::create_directories(root / d);
  }
  const std::vector<Marker> markers = dynamics::AutoMarkers(tree, 2, pull.rope);
  dynamics::NodeFrameWriter nodes(root / "simulate/nodes.bin");
  dynamics::MarkerTrackWriter tracks(markers, root / "simulate/markers.csv",
                                     root / "simulate/markers.json");
  dynamics::FrameRecorder* recorders[] = {&nodes, &tracks};
  const dynamics::SimulationResult sim = dynamics::RunSimulation(tree, options, recorders);
  WriteJson(root / "simulate/simulation.json",
            {{"format", "simtree.simulation"},
             {"version", 1},
             {"tree", "build/simready.json"},
             {"fps", options.fps},
             {"duration_s", options.duration_s},
             {"integrator", "exact"},
             {"pull",
              {{"branch", 1},
               {"point", {sim.pull_point.x(), sim.pull_point.y(), sim.pull_point.z()}},
               {"anchor", {pull.rope.anchor.x(), pull.rope.anchor.y(), pull.rope.anchor.z()}},
               {"tension_n", sim.pull_tension_n},
               {"hold_s", pull.hold_s},
               {"release_s", pull.release_s}}}});
  WriteTreeJson(tree, root / "build/simready.json");
  Tree bare = tree;
  for (Branch& b : bare.branches) b.material.reset();
  WriteTreeJson(bare, root / "reconstruct/static.json");
  WriteTrajectoriesCsv(tracks.trajectories(), root / "track/trajectories.csv");
  std::vector<MarkerLink> links;
  for (const Marker& m : markers) links.push_back({m.id, m.label, m.parent, m.branch});
  identification::IdentifyOptions identify;
  identify.compare_estimators = false;
  identify.estimator = identification::EstimatorKind::kInterpolatedSpectrum;  // fast
  identify.joint_poles = false;
  const auto result = identification::IdentifyMaterials(tracks.trajectories(), links, identify);
  identification::WriteMaterialsJson(
      identification::MaterialsFromIdentification(result, "track/trajectories.csv"),
      root / "identify/materials.json");
}

// Everything but preprocess/ (which needs point clouds): see the file comment.
inline void WriteResultFolder(const std::filesystem::path& root) {
  namespace fs = std::filesystem;
  WriteSimulatedStages(root);
  for (const char* d : {"register", "track/overlay", "render", "eval"}) {
    fs::create_directories(root / d);
  }
  WritePng(TestPicture(240, 120, 1), root / "register/before_after.png");
  WritePng(TestPicture(200, 160, 2), root / "reconstruct/picture.png");
  for (int i = 0; i < 8; ++i) {
    WritePng(TestPicture(160, 120, 10 + i), root / "track/overlay" / fmt::format("{:06d}.png", i));
  }
  for (int i = 0; i < 20; ++i) {
    WritePng(TestPicture(128, 48, 40 + i), root / "render" / fmt::format("{:06d}.png", i));
  }
  WriteFileAtomically(root / "track/boxes.csv", "frame,marker,x,y,w,h\n0,0,1,2,3,4\n");
  WriteJson(root / "register/poses.json",
            {{"format", "simtree.registration"},
             {"version", 1},
             {"anchor", "view_00"},
             {"registered", 2},
             {"views_total", 2},
             {"views",
              {{{"name", "view_00"}, {"registered", true}, {"status", "ok"}, {"pairs", 1}},
               {{"name", "view_01"}, {"registered", true}, {"status", "ok"}, {"pairs", 1}}}}});
  WriteJson(root / "register/pairs.json", {{"format", "simtree.registration_pairs"},
                                           {"version", 1},
                                           {"pairs",
                                            {{{"source", "view_01"},
                                              {"target", "view_00"},
                                              {"ok", true},
                                              {"status", "ok"},
                                              {"used", true},
                                              {"time_ms", 812.5},
                                              {"rmse_mm", 11.2},
                                              {"match_rate", 0.61}}}}});
  WriteJson(root / "eval/eval.json",
            {{"format", "simtree.eval"},
             {"version", 1},
             {"registration",
              {{"views", {{{"name", "view_01"}, {"rotation_deg", 0.12}, {"tree_rms_mm", 3.4}}}}}},
             {"tracking",
              {{"success_rate", 0.91}, {"precision", 0.88}, {"recall", 0.93}, {"f_score", 0.904}}},
             {"chain", {{"normalised_rmse", 0.21}, {"markers", 3}}}});
  WriteJson(root / "run.json", {{"format", "simtree.run"},
                                {"version", 1},
                                {"simtree", "0.1.0"},
                                {"capture", "capture-that-is-not-here"},
                                {"stages",
                                 {{{"name", "register"},
                                   {"status", "done"},
                                   {"wall_s", 2.5},
                                   {"summary", "2 of 2 views registered"},
                                   {"outputs", {"register/poses.json"}}},
                                  {{"name", "track"},
                                   {"status", "failed"},
                                   {"wall_s", 0.4},
                                   {"summary", "no markers <found>"},
                                   {"outputs", nlohmann::json::array()}},
                                  {{"name", "simulate"},
                                   {"status", "done"},
                                   {"wall_s", 0.2},
                                   {"summary", "4 s simulated"},
                                   {"outputs", {"simulate/nodes.bin"}}},
                                  {{"name", "eval"},
                                   {"status", "not run"},
                                   {"wall_s", nullptr},
                                   {"summary", ""},
                                   {"outputs", nlohmann::json::array()}}}}});
}

}  // namespace simtree::test
