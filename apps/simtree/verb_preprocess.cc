#include "cli_common.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterPreprocess(CLI::App& app) {
  AddNotBuiltVerb(app, "preprocess",
                  "RGB-D frames or point clouds to one clean tree cloud per view", "preprocessing");
}

}  // namespace simtree::cli
