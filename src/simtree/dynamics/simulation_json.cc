#include "simtree/dynamics/simulation_json.h"

#include "simtree/core/atomic_file.h"
#include "simtree/dynamics/oscillator.h"
#include "simtree/dynamics/rope.h"

namespace simtree::dynamics {
namespace {

using ojson = nlohmann::ordered_json;

ojson Vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

ojson PullJson(const PullSchedule& pull, const SimulationResult& result) {
  const Rope& r = pull.rope;
  return {{"branch", r.branch},
          {"arc_length_m", r.arc_length},
          {"point", Vec(result.pull_point)},
          {"anchor", Vec(r.anchor)},
          {"mode", ToString(r.mode)},
          {"force_n", r.force_n},
          {"displacement_m", r.displacement_m},
          {"tension_n", result.pull_tension_n},
          {"hold_s", pull.hold_s},
          {"release_s", pull.release_s}};
}

ojson WindJson(const WindOptions& wind, double heading_deg) {
  if (!wind.enabled) return nullptr;
  return {{"mean_speed_mps", wind.mean_speed_mps},
          {"heading_deg", heading_deg},
          {"turbulence_intensity", wind.turbulence_intensity},
          {"length_scale_m", wind.length_scale_m},
          {"seed", wind.seed}};
}

}  // namespace

SimulationJsonContent DescribeSimulation(const Tree& tree, const SimulationOptions& options,
                                         const SimulationResult& result) {
  SimulationJsonContent content;
  content.branches = tree.size();
  content.nodes = tree.NodeCount();
  content.options = options;
  content.result = result;
  if (content.options.pull) {
    Rope& rope = content.options.pull->rope;
    if (rope.arc_length < 0 && rope.branch >= 0 && rope.branch < tree.size()) {
      rope.arc_length = tree.branches[rope.branch].Length();
    }
  }
  return content;
}

ojson SimulationJson(const SimulationJsonContent& content) {
  const SimulationOptions& sim = content.options;
  const SimulationResult& result = content.result;
  ojson doc;
  doc["format"] = "simtree.simulation";
  doc["version"] = 1;
  doc["tree"] = content.tree_file;
  if (!content.material_file.empty()) doc["material_file"] = content.material_file;
  doc["branches"] = content.branches;
  doc["nodes"] = content.nodes;
  doc["duration_s"] = sim.duration_s;
  doc["fps"] = sim.fps;
  doc["frames"] = result.frames;
  doc["time_step_s"] = result.time_step_s;
  doc["steps"] = result.steps;
  if (content.record_model) doc["integrator"] = ToString(sim.dynamics.integrator);
  doc["base_excitation"] = sim.dynamics.base_excitation;
  doc["transfer_loads"] = sim.dynamics.transfer_loads;
  doc["gravity"] = sim.dynamics.gravity;
  if (content.record_model) doc["demo_mode_spread"] = sim.dynamics.demo_mode_spread;
  doc["pull"] = sim.pull ? PullJson(*sim.pull, result) : ojson(nullptr);
  if (!content.pull_fit.is_null()) doc["pull_fit"] = content.pull_fit;
  doc["wind"] = WindJson(sim.dynamics.wind, content.wind_heading_deg);
  doc["markers"] = content.markers;
  doc["outputs"] = content.outputs;
  return doc;
}

void WriteSimulationJson(const SimulationJsonContent& content, const std::filesystem::path& path) {
  WriteFileAtomically(path, SimulationJson(content).dump(2) + "\n");
}

}  // namespace simtree::dynamics
