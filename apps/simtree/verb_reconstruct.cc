#include "cli_common.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterReconstruct(CLI::App& app) {
  AddNotBuiltVerb(
      app, "reconstruct",
      "Static tree from a registered cloud (space colonization, MSAC trunk, allometric radii)",
      "static reconstruction");
}

}  // namespace simtree::cli
