#include "cli_common.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterView(CLI::App& app) {
  AddNotBuiltVerb(app, "view", "Interactive window: pull, release, tune materials", "viewer");
}

}  // namespace simtree::cli
