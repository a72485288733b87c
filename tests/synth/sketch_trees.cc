// Developer tool: grows preset trees and writes a sketch PNG (tree_sketch.h), a PLY tube mesh and
// a line of statistics per tree, to look at the species while tuning them.
//
//   build/bin/synth_sketch_trees OUT_DIR [species ...] [--seeds 1,2,3 | --seeds 1-30] [--bark]
//                                [--markers] [--json] [--fem]
//
// Species default to every preset; a species may also be a species JSON file. --json also writes
// each species' whole JSON (a starting point for a custom species). --fem adds the FEM oracle's
// first natural frequency and its damping ratio to each line (a whole-tree FEM: seconds a tree).

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "simtree/core/error.h"
#include "simtree/core/progress.h"
#include "simtree/core/tube_mesh.h"
#include "simtree/io/mesh_io.h"
#include "simtree/synth/detail/fem_model.h"
#include "simtree/synth/detail/fem_modes.h"
#include "simtree/synth/detail/marker_placement.h"
#include "simtree/synth/detail/tree_generator.h"
#include "simtree/synth/detail/tree_sketch.h"
#include "simtree/synth/species.h"

namespace {

// "1,2,3" or a range "1-30" (or both: "1-3,7").
std::vector<uint64_t> ParseSeeds(const std::string& list) {
  std::vector<uint64_t> seeds;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    const size_t dash = item.find('-');
    const uint64_t first = std::stoull(item.substr(0, dash));
    const uint64_t last = dash == std::string::npos ? first : std::stoull(item.substr(dash + 1));
    for (uint64_t seed = first; seed <= last; ++seed) seeds.push_back(seed);
  }
  return seeds;
}

// " f1 1.234 Hz zeta1 0.0456": the FEM oracle's first mode of the tree.
std::string FirstMode(const simtree::Tree& tree, const simtree::synth::SpeciesParams& species) {
  const simtree::synth::WoodProperties wood = species.wood.Properties();
  simtree::synth::ModesOptions modes;
  modes.count = 1;
  const double f1 =
      ComputeModes(simtree::synth::FemModel(tree, wood, SpeciesFemOptions(species)), modes)
          .frequency_hz[0];
  char text[64];
  std::snprintf(text, sizeof(text), ", f1 %.3f Hz zeta1 %.4f", f1, wood.DampingRatioAt(f1));
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace simtree;
  using namespace simtree::synth;
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: %s OUT_DIR [species ...] [--seeds 1,2|1-30] [--bark] [--markers] [--json] "
                 "[--fem]\n",
                 argv[0]);
    return 2;
  }
  const std::filesystem::path out = argv[1];
  std::vector<std::string> species;
  std::vector<uint64_t> seeds = {1};
  TreeSketchOptions sketch;
  bool markers = false;
  bool json = false;
  bool fem = false;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--seeds" && i + 1 < argc) {
      seeds = ParseSeeds(argv[++i]);
    } else if (arg == "--bark") {
      sketch.colour_by_level = false;
    } else if (arg == "--markers") {
      markers = true;
    } else if (arg == "--json") {
      json = true;
    } else if (arg == "--fem") {
      fem = true;
    } else {
      species.push_back(arg);
    }
  }
  if (species.empty()) species = SpeciesPresetNames();
  Progress::SetEnabled(false);  // no progress lines between the statistics lines
  try {
    std::filesystem::create_directories(out);
    for (const std::string& name : species) {
      const SpeciesParams params =
          std::filesystem::exists(name) ? ReadSpeciesJson(name) : SpeciesPreset(name);
      if (json) WriteSpeciesJson(params, out / (params.name + ".json"));
      for (const uint64_t seed : seeds) {
        const auto start = std::chrono::steady_clock::now();
        TreeGenerationResult result = GrowTree(params, seed);
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        Tree& tree = result.tree;
        std::string marker_levels;
        if (markers) {
          const MarkerPlacementResult placed = PlaceMarkers(
              tree, MarkerPlacementOptions{.camera_position = Eigen::Vector3d(0, -2.5, 1.2),
                                           .seed = seed});
          for (const int n : placed.markers_per_level) marker_levels += std::to_string(n) + " ";
          marker_levels += "hidden " + std::to_string(placed.hidden);
        }
        Eigen::Vector3d lo, hi;
        tree.Bounds(&lo, &hi);
        std::string per_level;
        for (const int n : result.branches_per_level) per_level += std::to_string(n) + " ";
        int thick = 0;
        for (const Branch& b : tree.branches) thick += b.nodes.front().radius >= 0.01;
        // The lowest node off the trunk (the trunk starts at the ground): below 0, under ground.
        double lowest = hi.z();
        for (const Branch& b : tree.branches) {
          if (b.parent < 0) continue;
          for (const Node& n : b.nodes) lowest = std::min(lowest, n.position.z());
        }
        std::printf(
            "%s seed %llu: height %.2f m, width %.2f x %.2f m, longest path %.2f m, trunk r "
            "%.1f mm, tip r %.2f mm, scale %.3f, branches %d (per level %s), >=1cm %d, nodes %d, "
            "lowest node off the trunk %.3f m (%d stopped at the ground), redrawn %d, crowded %d, "
            "budget %d, markers %zu "
            "(per level %s), %.0f ms%s\n",
            params.name.c_str(), static_cast<unsigned long long>(seed), hi.z(), hi.x() - lo.x(),
            hi.y() - lo.y(), result.longest_path_m, 1000 * tree.trunk().base().radius,
            1000 * result.tip_radius_m, result.scale, tree.size(), per_level.c_str(), thick,
            tree.NodeCount(), lowest, result.stopped_at_ground, result.redrawn_directions,
            result.dropped_crowded, result.dropped_budget, tree.markers.size(),
            marker_levels.c_str(), ms, fem ? FirstMode(tree, params).c_str() : "");
        const std::string stem = params.name + "_seed" + std::to_string(seed);
        WritePng(SketchTree(tree, sketch), out / (stem + ".png"));
        MeshWriteOptions mesh_options;
        mesh_options.colour_by_level_of = &tree;
        WriteMesh(BuildTubeMesh(tree), out / (stem + ".ply"), mesh_options);
      }
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
