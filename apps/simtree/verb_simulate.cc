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

void RegisterSimulate(CLI::App& app) {
  struct Args {
    std::string input, output, parameters, material_file;
    std::string markers = "auto";
    TreeFileOptions options;
    SimulationArgs run;
    int marker_level = 2;
    bool no_gltf = false, no_nodes = false;
    dynamics::AnimationOptions animation;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "simulate",
      "Animate a simulation-ready tree by modal analysis (paper Sec. III-E): pull a branch with a "
      "rope, hold, release; wind; writes node positions, marker tracks and a glTF animation");
  verb->add_option("input", args->input,
                   "Tree file with materials: .json, or .txt with "
                   "--material-file")
      ->required()
      ->check(CLI::ExistingFile);
  verb->add_option("-o,--out", args->output,
                   "Output folder: nodes.bin, markers.csv, markers.json, animation.glb, "
                   "simulation.json (replaced whole, or left untouched on error)")
      ->required();
  verb->add_option("--material-file", args->material_file,
                   "The authors' tree_parameters.txt ('frequency damping stiffness' per branch), "
                   "applied as every branch's material (same as --params)")
      ->check(CLI::ExistingFile);
  AddTreeFileOptions(verb, args->options, args->parameters);

  AddPullOptions(verb, args->run);
  AddRunOptions(verb, args->run);
  AddWindOptions(verb, args->run);
  AddModelOptions(verb, args->run);

  auto* out = verb->add_option_group("outputs");
  out->add_option("--markers", args->markers,
                  "Markers to track: 'auto' (the tree's own, else the tip of every branch up to "
                  "--marker-level and the pulled point) or 'tree' (the tree's own only)")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "tree"}));
  out->add_option("--marker-level", args->marker_level,
                  "Deepest branch level that gets an automatic tip marker")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  out->add_flag("--no-gltf", args->no_gltf, "Do not write animation.glb");
  out->add_flag("--no-nodes", args->no_nodes, "Do not write nodes.bin");
  out->add_option("--gltf-joints", args->animation.max_joints,
                  "Most joints in the glTF skin (one per node when the tree has fewer nodes)")
      ->capture_default_str()
      ->check(CLI::Range(1, kMaxGltfJoints));

  verb->footer(Examples({
      "simtree simulate tree.json --pull 3 --force 100 --hold 1 --release 3 --duration 10 "
      "--out sim/",
      "simtree simulate tree01.txt --material-file tree_parameters.txt --pull 1@2.5 --force 200 "
      "--release 2 --duration 15 --fps 30 --out sim01/",
      "simtree simulate tree.json --pull 5 --displacement 0.1 --anchor 2,0,0 --out pulled/",
      "simtree simulate tree.json --wind 8 --wind-heading-deg 90 --duration 20 --out windy/",
  }));

  verb->callback([args] {
    if (!args->material_file.empty()) args->parameters = args->material_file;
    FinishTreeFileOptions(args->options, args->parameters);
    std::vector<std::filesystem::path> inputs = {args->input};
    if (!args->parameters.empty()) inputs.push_back(args->parameters);
    RefuseToOverwriteInputs(args->output, inputs);
    const Tree tree = ReadTreeFile(args->input, args->options);
    dynamics::ValidateForSimulation(tree, args->input);

    FinishSimulationArgs(tree, args->run);
    const dynamics::SimulationOptions& sim = args->run.sim;

    std::vector<Marker> markers = tree.markers;
    if (markers.empty() && args->markers == "auto") {
      std::optional<dynamics::Rope> rope;
      if (sim.pull) rope = sim.pull->rope;
      markers = dynamics::AutoMarkers(tree, args->marker_level, rope);
    }

    AtomicDirectory folder(args->output);
    const std::filesystem::path dir = folder.path();
    std::vector<std::unique_ptr<dynamics::FrameRecorder>> owned;
    if (!args->no_nodes)
      owned.push_back(std::make_unique<dynamics::NodeFrameWriter>(dir / "nodes.bin"));
    if (!markers.empty()) {
      owned.push_back(std::make_unique<dynamics::MarkerTrackWriter>(markers, dir / "markers.csv",
                                                                    dir / "markers.json"));
    }
    if (!args->no_gltf) {
      owned.push_back(std::make_unique<dynamics::AnimationRecorder>(dir / "animation.glb", markers,
                                                                    args->animation));
    }
    std::vector<dynamics::FrameRecorder*> recorders;
    for (auto& r : owned) recorders.push_back(r.get());
    const dynamics::SimulationResult result = dynamics::RunSimulation(tree, sim, recorders);

    nlohmann::ordered_json doc;
    doc["format"] = "simtree.simulation";
    doc["version"] = 1;
    doc["tree"] = args->input;
    if (!args->parameters.empty()) doc["material_file"] = args->parameters;
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
    if (sim.pull) {
      const dynamics::Rope& r = sim.pull->rope;
      doc["pull"] = {
          {"branch", r.branch},
          {"arc_length_m", r.arc_length < 0 ? tree.branches[r.branch].Length() : r.arc_length},
          {"point", {result.pull_point.x(), result.pull_point.y(), result.pull_point.z()}},
          {"anchor", {r.anchor.x(), r.anchor.y(), r.anchor.z()}},
          {"mode", r.mode == dynamics::Rope::Mode::kForce ? "force" : "displacement"},
          {"force_n", r.force_n},
          {"displacement_m", r.displacement_m},
          {"tension_n", result.pull_tension_n},
          {"hold_s", sim.pull->hold_s},
          {"release_s", sim.pull->release_s}};
    } else {
      doc["pull"] = nullptr;
    }
    if (sim.dynamics.wind.enabled) {
      const dynamics::WindOptions& w = sim.dynamics.wind;
      doc["wind"] = {{"mean_speed_mps", w.mean_speed_mps},
                     {"heading_deg", args->run.wind_heading_deg},
                     {"turbulence_intensity", w.turbulence_intensity},
                     {"length_scale_m", w.length_scale_m},
                     {"seed", w.seed}};
    } else {
      doc["wind"] = nullptr;
    }
    doc["markers"] = markers.size();
    nlohmann::ordered_json outputs = nlohmann::ordered_json::array();
    if (!args->no_nodes) outputs.push_back("nodes.bin");
    if (!markers.empty()) {
      outputs.push_back("markers.csv");
      outputs.push_back("markers.json");
    }
    if (!args->no_gltf) outputs.push_back("animation.glb");
    outputs.push_back("simulation.json");
    doc["outputs"] = outputs;
    WriteFileAtomically(dir / "simulation.json", doc.dump(2) + "\n");
    folder.Commit();
    spdlog::info(
        "simulated {} s of {} branches ({} nodes): {} frames, {} steps of {:.4g} s in "
        "{:.2f} s; wrote {}",
        sim.duration_s, tree.size(), tree.NodeCount(), result.frames, result.steps,
        result.time_step_s, result.wall_seconds, args->output);
  });
}

}  // namespace simtree::cli
