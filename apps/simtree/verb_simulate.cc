#include <spdlog/spdlog.h>

#include <nlohmann/json.hpp>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/tree_file.h"
#include "simtree/core/units.h"
#include "simtree/dynamics/recorders.h"
#include "simtree/dynamics/simulation.h"
#include "verbs.h"

namespace simtree::cli {
namespace {

Eigen::Vector3d Vector(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

}  // namespace

void RegisterSimulate(CLI::App& app) {
  struct Args {
    std::string input, output, parameters, material_file, pull, integrator = "exact";
    std::string markers = "auto";
    TreeFileOptions options;
    SimulationOptions sim;
    std::optional<double> force, displacement;
    std::vector<double> anchor, direction;
    double hold = 1.0, release = 3.0;
    double wind = 0.0, wind_heading_deg = 0.0;
    int marker_level = 2;
    bool no_gltf = false, no_nodes = false, no_base_excitation = false, no_transfer = false;
    AnimationOptions animation;
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

  auto* pull = verb->add_option_group("pull test");
  pull->add_option("--pull", args->pull,
                   "Branch to pull: BRANCH (its tip) or BRANCH@S (S metres from its base)");
  pull->add_option("--force", args->force, "Rope tension at full pull (N)");
  pull->add_option("--displacement", args->displacement,
                   "Instead of a force: pull until the point has moved this far towards the "
                   "anchor, statically (m)");
  pull->add_option("--anchor", args->anchor,
                   "Where the rope is tied: X,Y,Z (world, m). Default: 2 m from the point, "
                   "straight down (sideways for an upright branch)")
      ->expected(3)
      ->delimiter(',');
  pull->add_option("--direction", args->direction,
                   "Instead of an anchor: the pull direction X,Y,Z (anchor 2 m that way)")
      ->expected(3)
      ->delimiter(',');
  pull->add_option("--hold", args->hold,
                   "Time (s) the pull is full and held from; it ramps up smoothly from t = 0 "
                   "(0 = all at once)")
      ->capture_default_str();
  pull->add_option("--release", args->release, "Time (s) the rope is let go")
      ->capture_default_str();

  verb->add_option("--duration", args->sim.duration_s, "Simulated time (s)")->capture_default_str();
  verb->add_option("--fps", args->sim.fps, "Frames per second written")->capture_default_str();
  verb->add_option("--time-step", args->sim.max_time_step_s,
                   "Longest simulation step (s); 0 = automatic, 1/20 of the fastest mode's period")
      ->capture_default_str();
  verb->add_option("--integrator", args->integrator,
                   "exact (unconditionally stable), semi-implicit-euler (the authors' demo) or "
                   "explicit-euler (the paper's text; diverges for stiff branches)")
      ->capture_default_str();

  auto* wind = verb->add_option_group("wind");
  wind->add_option("--wind", args->wind,
                   "Mean wind speed at the top of the crown (m/s); 0 = no wind")
      ->capture_default_str();
  wind->add_option("--wind-heading-deg", args->wind_heading_deg,
                   "Direction the wind blows towards, degrees counter-clockwise from +X")
      ->capture_default_str();
  wind->add_option("--turbulence", args->sim.dynamics.wind.turbulence_intensity,
                   "Gust strength: standard deviation over mean speed")
      ->capture_default_str();
  wind->add_option("--gust-length", args->sim.dynamics.wind.length_scale_m,
                   "Size of the gusts (m); 0 = the tree's height")
      ->capture_default_str();
  wind->add_option("--wind-seed", args->sim.dynamics.wind.seed, "Same seed, same gusts")
      ->capture_default_str();

  auto* model = verb->add_option_group("model");
  model->add_flag("--gravity", args->sim.dynamics.gravity,
                  "Let the tree sag under its own weight first (a scanned tree already has)");
  model->add_flag("--no-base-excitation", args->no_base_excitation,
                  "Children only ride their parents; their base's acceleration does not swing "
                  "them");
  model->add_flag("--no-load-transfer", args->no_transfer,
                  "A load bends only its own branch, not the ancestors");
  model->add_flag("--demo-mode-spread", args->sim.dynamics.demo_mode_spread,
                  "Spread each branch's modes as the authors' demo does (0.95 f, 1.05 f, f)");

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
    ValidateForSimulation(tree, args->input);

    SimulationOptions& sim = args->sim;
    sim.dynamics.integrator = ParseIntegrator(args->integrator, "--integrator");
    sim.dynamics.base_excitation = !args->no_base_excitation;
    sim.dynamics.transfer_loads = !args->no_transfer;
    if (args->wind < 0.0 || !std::isfinite(args->wind)) {
      throw InputError("", "--wind", fmt::format("expected a speed >= 0 m/s, got {}", args->wind));
    }
    sim.dynamics.wind.enabled = args->wind > 0.0;
    sim.dynamics.wind.mean_speed_mps = args->wind;
    const double heading = DegToRad(args->wind_heading_deg);
    sim.dynamics.wind.direction = {std::cos(heading), std::sin(heading), 0.0};

    if (!args->pull.empty()) {
      if (args->force.has_value() == args->displacement.has_value()) {
        throw InputError("", "--pull", "expected exactly one of --force N and --displacement M");
      }
      if (!args->anchor.empty() && !args->direction.empty()) {
        throw InputError("", "--anchor", "expected --anchor or --direction, not both");
      }
      const PullTarget target = ParsePullTarget(args->pull);
      PullSchedule schedule;
      schedule.rope.branch = target.branch;
      schedule.rope.arc_length = target.arc_length;
      if (args->force) {
        schedule.rope.force_n = *args->force;
      } else {
        schedule.rope.mode = Rope::Mode::kDisplacement;
        schedule.rope.displacement_m = *args->displacement;
      }
      const double s = ValidateRope(tree, schedule.rope, "--pull");
      const Eigen::Vector3d point = tree.branches[target.branch].PointAt(s);
      if (!args->anchor.empty()) {
        schedule.rope.anchor = Vector(args->anchor);
      } else {
        Eigen::Vector3d d = args->direction.empty() ? DefaultPullDirection(tree, target.branch, s)
                                                    : Vector(args->direction);
        if (!d.allFinite() || d.norm() < 1e-12) {
          throw InputError("", "--direction", "expected a non-zero finite direction");
        }
        schedule.rope.anchor = point + 2.0 * d.normalized();
      }
      ValidateRope(tree, schedule.rope, "--pull");
      schedule.hold_s = args->hold;
      schedule.release_s = args->release;
      sim.pull = schedule;
    } else if (args->force || args->displacement || !args->anchor.empty() ||
               !args->direction.empty()) {
      throw InputError("", "--pull",
                       "--force, --displacement, --anchor and --direction need --pull");
    }

    std::vector<Marker> markers = tree.markers;
    if (markers.empty() && args->markers == "auto") {
      std::optional<Rope> rope;
      if (sim.pull) rope = sim.pull->rope;
      markers = AutoMarkers(tree, args->marker_level, rope);
    }

    AtomicDirectory folder(args->output);
    const std::filesystem::path dir = folder.path();
    std::vector<std::unique_ptr<FrameRecorder>> owned;
    if (!args->no_nodes) owned.push_back(std::make_unique<NodeFrameWriter>(dir / "nodes.bin"));
    if (!markers.empty()) {
      owned.push_back(
          std::make_unique<MarkerTrackWriter>(markers, dir / "markers.csv", dir / "markers.json"));
    }
    if (!args->no_gltf) {
      owned.push_back(
          std::make_unique<AnimationRecorder>(dir / "animation.glb", markers, args->animation));
    }
    std::vector<FrameRecorder*> recorders;
    for (auto& r : owned) recorders.push_back(r.get());
    const SimulationResult result = RunSimulation(tree, sim, recorders);

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
      const Rope& r = sim.pull->rope;
      doc["pull"] = {
          {"branch", r.branch},
          {"arc_length_m", r.arc_length < 0 ? tree.branches[r.branch].Length() : r.arc_length},
          {"point", {result.pull_point.x(), result.pull_point.y(), result.pull_point.z()}},
          {"anchor", {r.anchor.x(), r.anchor.y(), r.anchor.z()}},
          {"mode", r.mode == Rope::Mode::kForce ? "force" : "displacement"},
          {"force_n", r.force_n},
          {"displacement_m", r.displacement_m},
          {"tension_n", result.pull_tension_n},
          {"hold_s", sim.pull->hold_s},
          {"release_s", sim.pull->release_s}};
    } else {
      doc["pull"] = nullptr;
    }
    if (sim.dynamics.wind.enabled) {
      const WindOptions& w = sim.dynamics.wind;
      doc["wind"] = {{"mean_speed_mps", w.mean_speed_mps},
                     {"heading_deg", args->wind_heading_deg},
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
