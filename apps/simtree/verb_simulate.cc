#include "cli_common.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterSimulate(CLI::App& app) {
  AddNotBuiltVerb(app, "simulate", "Animate a simulation-ready tree under pulls, releases and wind",
                  "dynamics");
}

}  // namespace simtree::cli
