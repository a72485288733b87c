// Developer tool: grows preset trees and writes a sketch PNG (tree_sketch.h), a PLY tube mesh and
// a line of statistics per tree, to look at the species while tuning them.
//
//   build/bin/synth_sketch_trees OUT_DIR [species ...] [--seeds 1,2,3] [--bark] [--markers]
//                                [--json]
//
// Species default to every preset; a species may also be a species JSON file. --json also writes
// each species' whole JSON (a starting point for a custom species).

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "simtree/core/error.h"
#include "simtree/core/tube_mesh.h"
#include "simtree/io/mesh_io.h"
#include "simtree/synth/marker_placement.h"
#include "simtree/synth/species.h"
#include "simtree/synth/tree_generator.h"
#include "simtree/synth/tree_sketch.h"

namespace {

std::vector<uint64_t> ParseSeeds(const std::string& list) {
  std::vector<uint64_t> seeds;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) seeds.push_back(std::stoull(item));
  return seeds;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace simtree;
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: %s OUT_DIR [species ...] [--seeds 1,2] [--bark] [--markers] [--json]\n",
                 argv[0]);
    return 2;
  }
  const std::filesystem::path out = argv[1];
  std::vector<std::string> species;
  std::vector<uint64_t> seeds = {1};
  TreeSketchOptions sketch;
  bool markers = false;
  bool json = false;
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
    } else {
      species.push_back(arg);
    }
  }
  if (species.empty()) species = SpeciesPresetNames();
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
        std::printf(
            "%s seed %llu: height %.2f m, width %.2f x %.2f m, trunk r %.1f mm, tip r %.2f mm, "
            "scale %.3f, branches %d (per level %s), >=1cm %d, nodes %d, redrawn %d, crowded %d, "
            "budget %d, markers %zu (per level %s), %.0f ms\n",
            params.name.c_str(), static_cast<unsigned long long>(seed), hi.z(), hi.x() - lo.x(),
            hi.y() - lo.y(), 1000 * tree.trunk().base().radius, 1000 * result.tip_radius_m,
            result.scale, tree.size(), per_level.c_str(), thick, tree.NodeCount(),
            result.redrawn_directions, result.dropped_crowded, result.dropped_budget,
            tree.markers.size(), marker_levels.c_str(), ms);
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
