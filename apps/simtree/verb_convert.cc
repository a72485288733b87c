#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/tree_file.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterConvert(CLI::App& app) {
  struct Args {
    std::string input, output, parameters, parameters_out;
    TreeFileOptions options;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "convert", "Convert a tree between the simtree JSON format and the authors' demo format");
  verb->add_option("input", args->input, "Tree file: .json (simtree) or .txt (authors' format)")
      ->required()
      ->check(CLI::ExistingFile);
  verb->add_option("output", args->output, "Tree file to write: .json or .txt")->required();
  AddTreeFileOptions(verb, args->options, args->parameters);
  verb->add_option("--params-out", args->parameters_out,
                   "With a .txt output: also write the materials as a tree_parameters.txt");
  verb->footer(Examples({
      "simtree convert tree01.txt tree01.json --params tree_parameters.txt",
      "simtree convert tree01.json tree01.txt --params-out tree_parameters.txt",
      "simtree convert scan.txt scan.json --scale 0.01 --z-up-input",
  }));
  verb->callback([args] {
    FinishTreeFileOptions(args->options, args->parameters);
    RefuseToOverwriteInputs(args->output, {args->input});
    if (!args->parameters.empty()) RefuseToOverwriteInputs(args->output, {args->parameters});
    const Tree tree = ReadTreeFile(args->input, args->options);
    TreeFileOptions out_options = args->options;
    out_options.legacy_parameters.reset();
    if (!args->parameters_out.empty()) {
      RefuseToOverwriteInputs(args->parameters_out, {args->input});
      if (!args->parameters.empty())
        RefuseToOverwriteInputs(args->parameters_out, {args->parameters});
      out_options.legacy_parameters = args->parameters_out;
    }
    WriteTreeFile(tree, args->output, out_options);
    spdlog::info("wrote {} ({} branches, {} nodes{})", args->output, tree.size(), tree.NodeCount(),
                 tree.IsSimulationReady() ? ", with materials" : "");
  });
}

}  // namespace simtree::cli
