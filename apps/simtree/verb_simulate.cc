#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "sim_options.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/tree_file.h"
#include "simtree/core/units.h"
#include "simtree/dynamics/recorders.h"
#include "simtree/dynamics/simulate.h"
#include "simtree/dynamics/simulation_json.h"
#include "verbs.h"

namespace simtree::cli {
namespace {

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
  std::vector<std::string> outputs;
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

// simulation.json: what was simulated, how, and what was written.
dynamics::SimulationJsonContent SimulationRecord(const Tree& tree, const SimulateArgs& args,
                                                 const dynamics::SimulationResult& result,
                                                 size_t markers, const Recorders& recorders) {
  dynamics::SimulationJsonContent content =
      dynamics::DescribeSimulation(tree, args.run.sim, result);
  content.tree_file = args.input;
  content.material_file = args.parameters;
  content.wind_heading_deg = args.run.wind_heading_deg;
  content.markers = markers;
  content.outputs = recorders.outputs;
  return content;
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
  dynamics::WriteSimulationJson(SimulationRecord(tree, args, result, markers.size(), recorders),
                                folder.path() / "simulation.json");
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
