#include "cli_common.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterRender(CLI::App& app) {
  AddNotBuiltVerb(app, "render", "Render frames and video without a display", "headless renderer");
}

}  // namespace simtree::cli
