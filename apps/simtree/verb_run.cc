#include "cli_common.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterRun(CLI::App& app) {
  AddNotBuiltVerb(app, "run", "The whole pipeline on a capture folder", "end-to-end run");
}

}  // namespace simtree::cli
