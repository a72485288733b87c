#include <spdlog/spdlog.h>

#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "sim_options.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/tree_file.h"
#include "simtree/core/units.h"
#include "simtree/dynamics/recorders.h"
#include "simtree/dynamics/simulate.h"
#include "verbs.h"

namespace simtree::cli {
namespace {

using ojson = nlohmann::ordered_json;

struct SimulateArgs {
  std::string input, output, parameters, material_file;
  std::string markers = "auto";
  TreeFileOptions options;
  SimulationArgs run;
  int marker_level = 2;
  bool no_gltf = false, no_nodes = false;
  dynamics::AnimationOptions animation;
};

void AddOutputOptions(CLI::App* verb, SimulateArgs& args) {
  auto* out = verb->add_option_group("outputs");
  out->add_option("--markers", args.markers,
                  "Markers to track: 'auto' (the tree's own, else the tip of every branch up to "
                  "--marker-level and the pulled point) or 'tree' (the tree's own only)")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "tree"}));
  out->add_option("--marker-level", args.marker_level,
                  "Deepest branch level that gets an automatic tip marker")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  out->add_flag("--no-gltf", args.no_gltf, "Do not write animation.glb");
  out->add_flag("--no-nodes", args.no_nodes, "Do not write nodes.bin");
  out->add_option("--gltf-joints", args.animation.max_joints,
                  "Most joints in the glTF skin (one per node when the tree has fewer nodes)")
      ->capture_default_str()
      ->check(CLI::Range(1, kMaxGltfJoints));
}

void AddSimulateOptions(CLI::App* verb, SimulateArgs& args) {
  verb->add_option("input", args.input,
                   "Tree file with materials: .json, or .txt with "
                   "--material-file")
      ->required()
      ->check(CLI::ExistingFile);
  verb->add_option("-o,--out", args.output,
                   "Output folder: nodes.bin, markers.csv, markers.json, animation.glb, "
                   "simulation.json (replaced whole, or left untouched on error)")
      ->required();
  verb->add_option("--material-file", args.material_file,
                   "The authors' tree_parameters.txt ('frequency damping stiffness' per branch), "
                   "applied as every branch's material (same as --params)")
      ->check(CLI::ExistingFile);
  AddTreeFileOptions(verb, args.options, args.parameters);
  AddPullOptions(verb, args.run);
  AddRunOptions(verb, args.run);
  AddWindOptions(verb, args.run);
  AddModelOptions(verb, args.run);
  AddOutputOptions(verb, args);
  verb->footer(Examples({
      "simtree simulate tree.json --pull 3 --force 100 --hold 1 --release 3 --duration 10 "
      "--out sim/",
      "simtree simulate tree01.txt --material-file tree_parameters.txt --pull 1@2.5 --force 200 "
      "--release 2 --duration 15 --fps 30 --out sim01/",
      "simtree simulate tree.json --pull 5 --displacement 0.1 --anchor 2,0,0 --out pulled/",
      "simtree simulate tree.json --wind 8 --wind-heading-deg 90 --duration 20 --out windy/",
  }));
}

// The tree's own markers, else with --markers auto a tip marker up to --marker-level and the
// pulled point.
std::vector<Marker> MarkersToTrack(const Tree& tree, const SimulateArgs& args) {
  if (!tree.markers.empty() || args.markers != "auto") return tree.markers;
  std::optional<dynamics::Rope> rope;
  if (args.run.sim.pull) rope = args.run.sim.pull->rope;
  return dynamics::AutoMarkers(tree, args.marker_level, rope);
}

// One recorder per file the options ask for, writing into `dir`; `outputs` lists the files.
struct Recorders {
  std::vector<std::unique_ptr<dynamics::FrameRecorder>> owned;
  std::vector<dynamics::FrameRecorder*> all;
  ojson outputs = ojson::array();
};

Recorders MakeRecorders(const std::filesystem::path& dir, const SimulateArgs& args,
                        const std::vector<Marker>& markers) {
  Recorders r;
  if (!args.no_nodes) {
    r.owned.push_back(std::make_unique<dynamics::NodeFrameWriter>(dir / "nodes.bin"));
    r.outputs.push_back("nodes.bin");
  }
  if (!markers.empty()) {
    r.owned.push_back(std::make_unique<dynamics::MarkerTrackWriter>(markers, dir / "markers.csv",
                                                                    dir / "markers.json"));
    r.outputs.push_back("markers.csv");
    r.outputs.push_back("markers.json");
  }
  if (!args.no_gltf) {
    r.owned.push_back(std::make_unique<dynamics::AnimationRecorder>(dir / "animation.glb", markers,
                                                                    args.animation));
    r.outputs.push_back("animation.glb");
  }
  r.outputs.push_back("simulation.json");
  for (auto& recorder : r.owned) r.all.push_back(recorder.get());
  return r;
}

ojson PullJson(const Tree& tree, const dynamics::PullSchedule& pull,
               const dynamics::SimulationResult& result) {
  const dynamics::Rope& r = pull.rope;
  const Eigen::Vector3d& p = result.pull_point;
  return {{"branch", r.branch},
          {"arc_length_m", r.arc_length < 0 ? tree.branches[r.branch].Length() : r.arc_length},
          {"point", {p.x(), p.y(), p.z()}},
          {"anchor", {r.anchor.x(), r.anchor.y(), r.anchor.z()}},
          {"mode", ToString(r.mode)},
          {"force_n", r.force_n},
          {"displacement_m", r.displacement_m},
          {"tension_n", result.pull_tension_n},
          {"hold_s", pull.hold_s},
          {"release_s", pull.release_s}};
}

// simulation.json: what was simulated, how, and what was written.
ojson SimulationJson(const Tree& tree, const SimulateArgs& args,
                     const dynamics::SimulationResult& result, size_t markers,
                     const ojson& outputs) {
  const dynamics::SimulationOptions& sim = args.run.sim;
  ojson doc;
  doc["format"] = "simtree.simulation";
  doc["version"] = 1;
  doc["tree"] = args.input;
  if (!args.parameters.empty()) doc["material_file"] = args.parameters;
  doc["branches"] = tree.size();
  doc["nodes"] = tree.NodeCount();
  doc["duration_s"] = sim.duration_s;
  doc["fps"] = sim.fps;
  doc["frames"] = result.frames;
  doc["time_step_s"] = result.time_step_s;
  doc["steps"] = result.steps;
  doc["integrator"] = ToString(sim.dynamics.integrator);
  doc["base_excitation"] = sim.dynamics.base_excitation;
  doc["transfer_loads"] = sim.dynamics.transfer_loads;
  doc["gravity"] = sim.dynamics.gravity;
  doc["demo_mode_spread"] = sim.dynamics.demo_mode_spread;
  doc["pull"] = sim.pull ? PullJson(tree, *sim.pull, result) : ojson(nullptr);
  if (sim.dynamics.wind.enabled) {
    const dynamics::WindOptions& w = sim.dynamics.wind;
    doc["wind"] = {{"mean_speed_mps", w.mean_speed_mps},
                   {"heading_deg", args.run.wind_heading_deg},
                   {"turbulence_intensity", w.turbulence_intensity},
                   {"length_scale_m", w.length_scale_m},
                   {"seed", w.seed}};
  } else {
    doc["wind"] = nullptr;
  }
  doc["markers"] = markers;
  doc["outputs"] = outputs;
  return doc;
}

void Simulate(SimulateArgs& args) {
  if (!args.material_file.empty()) args.parameters = args.material_file;
  FinishTreeFileOptions(args.options, args.parameters);
  std::vector<std::filesystem::path> inputs = {args.input};
  if (!args.parameters.empty()) inputs.push_back(args.parameters);
  RefuseToOverwriteInputs(args.output, inputs);
  const Tree tree = ReadTreeFile(args.input, args.options);
  dynamics::ValidateForSimulation(tree, args.input);
  FinishSimulationArgs(tree, args.run);
  // Every option checked before the output folder exists.
  dynamics::ValidateSimulation(tree, args.run.sim);
  args.animation.Validate();
  const std::vector<Marker> markers = MarkersToTrack(tree, args);

  AtomicDirectory folder(args.output);
  const Recorders recorders = MakeRecorders(folder.path(), args, markers);
  const dynamics::SimulationResult result =
      dynamics::RunSimulation(tree, args.run.sim, recorders.all);
  const ojson doc = SimulationJson(tree, args, result, markers.size(), recorders.outputs);
  WriteFileAtomically(folder.path() / "simulation.json", doc.dump(2) + "\n");
  folder.Commit();
  spdlog::info(
      "simulated {} s of {} branches ({} nodes): {} frames, {} steps of {:.4g} s in "
      "{:.2f} s; wrote {}",
      args.run.sim.duration_s, tree.size(), tree.NodeCount(), result.frames, result.steps,
      result.time_step_s, result.wall_seconds, args.output);
}

}  // namespace

void RegisterSimulate(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* verb = app.add_subcommand(
      "simulate",
      "Animate a simulation-ready tree by modal analysis (paper Sec. III-E): pull a branch with a "
      "rope, hold, release; wind; writes node positions, marker tracks and a glTF animation");
  AddSimulateOptions(verb, *args);
  verb->callback([args] { Simulate(*args); });
}

}  // namespace simtree::cli
