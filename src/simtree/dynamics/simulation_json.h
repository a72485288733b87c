#pragma once
// simulation.json, the record of one simulation run beside the files it wrote: the tree, the frame
// rate and length, the step, the model's switches, the pull (and the fit it came from, for the
// run's simulate stage), the wind, the markers and the list of files (docs/formats.md). Written by
// `simtree simulate` and by the simulate stage of `simtree run`.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "simtree/core/tree.h"
#include "simtree/dynamics/simulate.h"

namespace simtree::dynamics {

// What simulation.json records. DescribeSimulation fills the run's part; the caller names the
// files and adds what only it knows.
struct SimulationJsonContent {
  std::string tree_file;      // the simulated tree's file, as the caller names it
  std::string material_file;  // the materials file applied to it; "" = none (no key)
  int branches = 0;
  int nodes = 0;
  SimulationOptions options;  // what was simulated; a pull's arc length is resolved (>= 0)
  SimulationResult result;
  // Write "integrator" and "demo_mode_spread"; the run's simulate stage, which always uses the
  // defaults, leaves them out.
  bool record_model = true;
  double wind_heading_deg = 0.0;          // deg: the wind's heading as given (with the wind on)
  // The run's fit of the pull it replays, written after "pull" as given (null: no key).
  nlohmann::ordered_json pull_fit;
  size_t markers = 0;                     // markers tracked
  std::vector<std::string> outputs;       // the files written, simulation.json included
};

// The content of a run of `options` on `tree` that gave `result`: branch and node counts, the
// options with a pull at the tip (negative arc length) given its branch's length, the result.
SimulationJsonContent DescribeSimulation(const Tree& tree, const SimulationOptions& options,
                                         const SimulationResult& result);

// The document, keys in a fixed order.
nlohmann::ordered_json SimulationJson(const SimulationJsonContent& content);

// Writes SimulationJson(content) to `path` atomically, indented by 2 with a final newline.
// Throws IoError when it cannot be written.
void WriteSimulationJson(const SimulationJsonContent& content, const std::filesystem::path& path);

}  // namespace simtree::dynamics
