#pragma once
// Options shared by `view` and `render`: the tree file (with materials, or the demo's per-level
// defaults), leaves and how the tree is drawn.

#include <string>

#include <CLI/CLI.hpp>

#include "simtree/core/tree_file.h"
#include "simtree/viewer/scene_assets.h"
#include "simtree/viewer/scene_renderer.h"

namespace simtree::cli {

struct SceneArgs {
  std::string input, parameters, material_file;
  TreeFileOptions tree_options;
  viewer::FoliageSource foliage;
  std::string colouring = "bark";
  bool no_grid = false;
};

// The tree argument, --material-file/--params, --scale, --z-up-input.
void AddTreeInput(CLI::App* verb, SceneArgs& args);
// --leaves, --leaf-density, --leaf-length, --leaf-seed, --max-leaves, --colour, --no-grid.
void AddSceneOptions(CLI::App* verb, SceneArgs& args);

// Reads the tree; a branch without a material gets the demo's value for its level (logged).
// Throws InputError when the tree still cannot be simulated.
Tree LoadTreeForViewing(SceneArgs& args);
// The style the options ask for.
viewer::SceneStyle StyleFromArgs(const SceneArgs& args);

}  // namespace simtree::cli
