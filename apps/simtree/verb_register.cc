#include "cli_common.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterRegister(CLI::App& app) {
  AddNotBuiltVerb(
      app, "register",
      "Register the multi-view scans into one cloud (key-region skeletons, SAC-IA, ICP)",
      "registration");
}

}  // namespace simtree::cli
