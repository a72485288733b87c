#include "cli_common.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterEval(CLI::App& app) {
  AddNotBuiltVerb(app, "eval", "Score outputs against synth ground truth", "evaluation");
}

}  // namespace simtree::cli
