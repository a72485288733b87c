#include "cli_common.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterIdentify(CLI::App& app) {
  AddNotBuiltVerb(app, "identify",
                  "Natural frequency and damping per marker link from tracked trajectories",
                  "material identification");
}

}  // namespace simtree::cli
