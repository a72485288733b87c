#include "cli_common.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterSynth(CLI::App& app) {
  AddNotBuiltVerb(app, "synth",
                  "Make a synthetic capture with ground truth: tree, FEM truth, multi-view scans, "
                  "pull-test stream",
                  "synthetic capture bench");
}

}  // namespace simtree::cli
