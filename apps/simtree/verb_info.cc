#include <cstdio>

#include "cli_common.h"
#include "simtree/core/tree_file.h"
#include "simtree/core/tree_summary.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterInfo(CLI::App& app) {
  struct Args {
    std::string input, parameters;
    TreeFileOptions options;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand("info", "Validate a tree file and print what it holds");
  verb->add_option("input", args->input, "Tree file: .json or .txt")
      ->required()
      ->check(CLI::ExistingFile);
  AddTreeFileOptions(verb, args->options, args->parameters);
  verb->footer(
      Examples({"simtree info tree.json", "simtree info tree01.txt --params tree_parameters.txt"}));
  verb->callback([args] {
    FinishTreeFileOptions(args->options, args->parameters);
    const Tree tree = ReadTreeFile(args->input, args->options);
    std::printf("%s\n%s\n", args->input.c_str(), FormatSummary(Summarize(tree)).c_str());
  });
}

}  // namespace simtree::cli
