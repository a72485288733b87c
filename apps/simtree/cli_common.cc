#include "cli_common.h"

#include "simtree/core/error.h"

namespace simtree::cli {

CLI::App* AddNotBuiltVerb(CLI::App& app, const std::string& name, const std::string& description,
                          const std::string& pipeline_stage) {
  CLI::App* verb = app.add_subcommand(name, description + " [not built yet]");
  // Runs as soon as the verb is seen, before its arguments (which it cannot know yet) are parsed.
  verb->preparse_callback([name, pipeline_stage](size_t) {
    throw NotBuiltError("simtree " + name + ": the " + pipeline_stage +
                        " stage is not built yet (see README.md, Status)");
  });
  return verb;
}

void AddTreeFileOptions(CLI::App* verb, TreeFileOptions& options, std::string& parameters_path) {
  verb->add_option("--scale", options.legacy.scale,
                   "Metres per unit of the authors' .txt format (their trees are ~16 units tall)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  verb->add_flag("!--z-up-input", options.legacy.y_up,
                 "The .txt file is already Z-up (the authors' files are Y-up)");
  verb->add_option("--params", parameters_path,
                   "The authors' tree_parameters.txt: one 'frequency damping stiffness' line per "
                   "branch, applied as materials")
      ->check(CLI::ExistingFile);
}

void FinishTreeFileOptions(TreeFileOptions& options, const std::string& parameters_path) {
  if (!parameters_path.empty()) options.legacy_parameters = parameters_path;
}

std::string Examples(std::initializer_list<std::string> lines) {
  std::string out = "\nExamples:\n";
  for (const std::string& line : lines) out += "  " + line + "\n";
  return out;
}

}  // namespace simtree::cli
