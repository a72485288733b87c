#include "cli_common.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterTrack(CLI::App& app) {
  AddNotBuiltVerb(app, "track", "Track the red tape markers through a pull-test stream in 3D",
                  "marker tracking");
}

}  // namespace simtree::cli
