#include "scene_options.h"

#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/dynamics/tree_dynamics.h"
#include "simtree/viewer/demo_materials.h"

namespace simtree::cli {

void AddTreeInput(CLI::App* verb, SceneArgs& args) {
  verb->add_option("input", args.input,
                   "Tree file: .json, or the authors' .txt (with --material-file, or the demo's "
                   "per-level materials)")
      ->required()
      ->check(CLI::ExistingFile);
  verb->add_option("--material-file", args.material_file,
                   "The authors' tree_parameters.txt, applied as every branch's material (same "
                   "as --params)")
      ->check(CLI::ExistingFile);
  AddTreeFileOptions(verb, args.tree_options, args.parameters);
}

void AddSceneOptions(CLI::App* verb, SceneArgs& args) {
  auto* look = verb->add_option_group("look");
  look->add_option("--leaves", args.foliage.leaves,
                   "Leaf model folder (leaf.txt, leafup.bmp, leafdown.bmp, petiole.bmp, "
                   "branch.bmp), 'none', or 'auto': ../leaf_model/apple_leaf beside the tree's "
                   "folder when there is one")
      ->capture_default_str();
  look->add_option("--leaf-density", args.foliage.placement.leaves_per_metre,
                   "Leaves per metre along each terminal branch")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  look->add_option("--leaf-length", args.foliage.placement.leaf_length_m,
                   "Leaf length, petiole included (m)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  look->add_option("--max-leaves", args.foliage.placement.max_leaves, "Most leaves on the tree")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  look->add_option("--leaf-seed", args.foliage.placement.seed, "Same seed, same leaves")
      ->capture_default_str();
  look->add_option("--colour", args.colouring,
                   "Branches: bark (texture), level (the demo's colour per level) or source "
                   "(measured green, interpolated amber, default grey)")
      ->capture_default_str()
      ->check(CLI::IsMember({"bark", "level", "source"}));
  look->add_flag("--no-grid", args.no_grid, "No ground grid");
}

Tree LoadTreeForViewing(SceneArgs& args) {
  if (!args.material_file.empty()) args.parameters = args.material_file;
  FinishTreeFileOptions(args.tree_options, args.parameters);
  Tree tree = ReadTreeFile(args.input, args.tree_options);
  const int filled = viewer::FillMissingMaterials(tree);
  if (filled > 0) {
    spdlog::warn(
        "{}: {} of {} branches have no material: using the authors' demo values per "
        "level (source 'default')",
        args.input, filled, tree.size());
  }
  dynamics::ValidateForSimulation(tree, args.input);
  return tree;
}

viewer::SceneStyle StyleFromArgs(const SceneArgs& args) {
  viewer::SceneStyle style;
  style.grid = !args.no_grid;
  if (args.colouring == "level") style.colouring = viewer::BranchColouring::kLevel;
  if (args.colouring == "source") style.colouring = viewer::BranchColouring::kSource;
  return style;
}

}  // namespace simtree::cli
