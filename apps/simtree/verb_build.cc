#include "cli_common.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterBuild(CLI::App& app) {
  AddNotBuiltVerb(app, "build", "Static tree + materials to a simulation-ready tree",
                  "simulation-ready build");
}

}  // namespace simtree::cli
