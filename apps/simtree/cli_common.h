#pragma once
// Small pieces every verb shares: the "not built yet" verb, the legacy-format options, examples in
// --help.

#include <string>

#include <CLI/CLI.hpp>

#include "simtree/core/tree_file.h"

namespace simtree::cli {

// A verb whose stage is not built yet: it shows in --help and exits 2 saying so.
CLI::App* AddNotBuiltVerb(CLI::App& app, const std::string& name, const std::string& description,
                          const std::string& pipeline_stage);

// Adds --scale, --z-up-input (for .txt files) and --params to `verb`, filling `options`.
void AddTreeFileOptions(CLI::App* verb, TreeFileOptions& options, std::string& parameters_path);
// Applies the parsed --params path to `options`.
void FinishTreeFileOptions(TreeFileOptions& options, const std::string& parameters_path);

// The footer of a verb's --help with example command lines.
std::string Examples(std::initializer_list<std::string> lines);

}  // namespace simtree::cli
