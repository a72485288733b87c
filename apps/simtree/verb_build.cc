#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/tree_file.h"
#include "simtree/core/tree_summary.h"
#include "simtree/identification/materials_file.h"
#include "simtree/simready/build.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterBuild(CLI::App& app) {
  struct Args {
    std::string input, materials, output, parameters;
    TreeFileOptions tree_options;
    simready::BuildOptions build;
    bool no_subtree_mass = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "build",
      "Static tree + identified materials -> simulation-ready tree (paper III-D): three modes, "
      "modal mass and stiffness and a frame per branch; unmeasured branches interpolated");
  verb->add_option("tree", args->input, "Static tree: .json (simtree) or .txt (authors' format)")
      ->required()
      ->check(CLI::ExistingFile);
  verb->add_option("-m,--materials", args->materials, "materials.json from `simtree identify`")
      ->required()
      ->check(CLI::ExistingFile);
  verb->add_option("-o,--out", args->output, "Simulation-ready tree: .json or .txt")->required();
  verb->add_option("--density", args->build.wood_density_kg_m3,
                   "Green wood density (kg/m^3) for the branch masses")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  verb->add_flag("--no-subtree-mass", args->no_subtree_mass,
                 "Modal mass of a branch's own wood only (default: the sub-trees riding on it "
                 "count too)");
  verb->add_flag("--depth-first-ids", args->build.renumber_depth_first,
                 "Renumber branches in depth-first order (each sub-tree gets consecutive ids)");
  AddTreeFileOptions(verb, args->tree_options, args->parameters);
  verb->footer(Examples({
      "simtree build static.json --materials materials.json --out simready.json",
      "simtree build static.json -m materials.json -o simready.json --density 750",
  }));
  verb->callback([args] {
    FinishTreeFileOptions(args->tree_options, args->parameters);
    RefuseToOverwriteInputs(args->output, {args->input, args->materials});
    args->build.include_subtree_mass = !args->no_subtree_mass;
    const Tree static_tree = ReadTreeFile(args->input, args->tree_options);
    const identification::MaterialsFile materials =
        identification::ReadMaterialsJson(args->materials);
    simready::BuildReport report;
    const Tree tree =
        simready::BuildSimulationReadyTree(static_tree, materials, args->build, &report);
    WriteTreeFile(tree, args->output, args->tree_options);
    spdlog::info("{} branches measured, {} interpolated: {}", report.measured, report.interpolated,
                 report.interpolation.Describe());
    spdlog::info("wood {:.0f} kg/m^3, tree mass {:.2f} kg", args->build.wood_density_kg_m3,
                 report.total_mass_kg);
    std::printf("%s\n", FormatSummary(Summarize(tree)).c_str());
    spdlog::info("wrote {}", args->output);
  });
}

}  // namespace simtree::cli
