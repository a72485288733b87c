#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/tree_file.h"
#include "simtree/core/tree_summary.h"
#include "simtree/identification/materials_file.h"
#include "simtree/simready/build.h"
#include "verbs.h"

namespace simtree::cli {

namespace {

// "1.2,0.03" -> frequency 1.2 Hz, damping ratio 0.03 (checked by the build).
simready::AssumedMaterial ParseDefaultMaterial(const std::string& text) {
  const size_t comma = text.find(',');
  simready::AssumedMaterial assumed;
  try {
    if (comma == std::string::npos) throw std::invalid_argument("no comma");
    size_t used_f = 0, used_z = 0;
    const std::string f = text.substr(0, comma), z = text.substr(comma + 1);
    assumed.frequency_hz = std::stod(f, &used_f);
    assumed.damping_ratio = std::stod(z, &used_z);
    if (used_f != f.size() || used_z != z.size()) throw std::invalid_argument("trailing text");
  } catch (const std::exception&) {
    throw InputError("build", "--default-material",
                     fmt::format("expected F,ZETA (a frequency in Hz and a damping ratio, e.g. "
                                 "1.2,0.03), got \"{}\"",
                                 text));
  }
  assumed.origin = "given with --default-material";
  try {
    assumed.Validate();
  } catch (const OptionError& e) {
    throw InputError("build", "--default-material",
                     fmt::format("{}: {} (from \"{}\")", e.field(), e.expected(), text));
  }
  return assumed;
}

}  // namespace

void RegisterBuild(CLI::App& app) {
  struct Args {
    std::string input, materials, output, parameters, species, default_material;
    TreeFileOptions tree_options;
    simready::BuildOptions build;
    bool no_subtree_mass = false, keep_uncertain = false, trust_all = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "build",
      "Static tree + identified materials -> simulation-ready tree (paper III-D): three modes, "
      "modal mass and stiffness and a frame per branch; unmeasured branches interpolated. "
      "Without a pull test, --species or --default-material give every branch assumed values");
  verb->add_option("tree", args->input, "Static tree: .json (simtree) or .txt (authors' format)")
      ->required()
      ->check(CLI::ExistingFile);
  CLI::Option* materials =
      verb->add_option("-m,--materials", args->materials, "materials.json from `simtree identify`")
          ->check(CLI::ExistingFile);
  CLI::Option* species =
      verb->add_option("--species", args->species,
                       "No pull test: every branch gets the middle of the paper's Table IV "
                       "ranges for this species (acer_palmatum, magnolia, acer_rubrum), marked "
                       "assumed");
  CLI::Option* default_material =
      verb->add_option("--default-material", args->default_material,
                       "No pull test: every branch gets this frequency (Hz) and damping ratio, "
                       "F,ZETA (e.g. 1.2,0.03), marked assumed");
  materials->excludes(species)->excludes(default_material);
  species->excludes(default_material);
  verb->add_option("-o,--out", args->output, "Simulation-ready tree: .json or .txt")->required();
  verb->add_option("--density", args->build.wood_density_kg_m3,
                   "Green wood density (kg/m^3) for the branch masses")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  verb->add_flag("--no-subtree-mass", args->no_subtree_mass,
                 "Modal mass of a branch's own wood only (default: the sub-trees riding on it "
                 "count too)");
  verb->add_flag("--keep-uncertain", args->keep_uncertain,
                 "Measured values flagged uncertain keep their own value (still flagged; default: "
                 "the interpolation replaces them when it is more certain)");
  verb->add_flag("--trust-all", args->trust_all,
                 "Flag no measured value as uncertain (every measured branch keeps its value)");
  verb->add_option("--max-frequency-sd", args->build.uncertainty.max_frequency_relative_std,
                   "A measured frequency whose sd is over this share of its value is uncertain")
      ->capture_default_str();
  verb->add_option("--max-damping-sd", args->build.uncertainty.max_damping_relative_std,
                   "A measured damping ratio whose sd is over this share of its value is uncertain "
                   "(inf: off)")
      ->capture_default_str();
  verb->add_option("--max-z", args->build.uncertainty.max_z,
                   "A measured frequency this many sd from what the other branches predict is "
                   "uncertain (inf: off)")
      ->capture_default_str();
  verb->add_flag("--weight-by-sd", args->build.interpolation.weight_by_uncertainty,
                 "Weight the interpolation's fit by each measured value's 1/sd^2 (floored at the "
                 "median sd)");
  verb->add_flag("--depth-first-ids", args->build.renumber_depth_first,
                 "Renumber branches in depth-first order (each sub-tree gets consecutive ids)");
  AddTreeFileOptions(verb, args->tree_options, args->parameters);
  verb->footer(Examples({
      "simtree build static.json --materials materials.json --out simready.json",
      "simtree build static.json -m materials.json -o simready.json --density 750",
      "simtree build static.json --species magnolia -o simready.json      # no pull test",
      "simtree build static.json --default-material 1.2,0.03 -o simready.json",
  }));
  verb->callback([args] {
    FinishTreeFileOptions(args->tree_options, args->parameters);
    if (args->materials.empty() && args->species.empty() && args->default_material.empty()) {
      throw InputError("build", "--materials",
                       "expected materials.json from `simtree identify` (a pull test), or, "
                       "without one, --species NAME or --default-material F,ZETA");
    }
    RefuseToOverwriteInputs(args->output, {args->input, args->materials});
    args->build.include_subtree_mass = !args->no_subtree_mass;
    args->build.uncertainty.replace = !args->keep_uncertain;
    args->build.uncertainty.flag = !args->trust_all;
    const Tree static_tree = ReadTreeFile(args->input, args->tree_options);
    simready::BuildReport report;
    Tree tree;
    if (!args->materials.empty()) {
      tree = simready::BuildSimulationReadyTree(
          static_tree, identification::ReadMaterialsJson(args->materials), args->build, &report);
      spdlog::info("{} branches measured, {} interpolated: {}", report.measured,
                   report.interpolated, report.interpolation.Describe());
      if (report.flagged > 0) {
        spdlog::warn("{} measured values flagged uncertain, {} replaced by the interpolation:",
                     report.flagged, report.replaced);
        for (const std::string& line : report.flagged_why) spdlog::warn("  {}", line);
      }
    } else {
      const simready::AssumedMaterial assumed = args->species.empty()
                                                    ? ParseDefaultMaterial(args->default_material)
                                                    : simready::AssumedMaterialOf(args->species);
      tree = simready::BuildAssumedSimulationReadyTree(static_tree, assumed, args->build, &report);
      spdlog::warn("no pull test: all {} branches assumed at {:.3g} Hz, damping {:.3g} ({})",
                   report.assumed, assumed.frequency_hz, assumed.damping_ratio, assumed.origin);
    }
    WriteTreeFile(tree, args->output, args->tree_options);
    spdlog::info("wood {:.0f} kg/m^3, tree mass {:.2f} kg", args->build.wood_density_kg_m3,
                 report.total_mass_kg);
    std::printf("%s\n", FormatSummary(Summarize(tree)).c_str());
    spdlog::info("wrote {}", args->output);
  });
}

}  // namespace simtree::cli
