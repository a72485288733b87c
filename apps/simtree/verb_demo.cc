#include <cstdio>
#include <memory>

#include "cli_common.h"
#include "simtree/pipeline/demo.h"
#include "verbs.h"

namespace simtree::cli {

void PrintRunTable(const pipeline::RunResult& result);  // verb_run.cc

void RegisterDemo(CLI::App& app) {
  struct Args {
    std::string output = "out/demo";
    pipeline::DemoOptions options;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "demo",
      "The pipeline end to end on a synthetic capture: synth (small: 4 views, a 7 s pull) into "
      "OUT/capture, run into OUT/result, eval against the truth, and the path of the report to "
      "open. A second demo reuses the capture and every unchanged stage.");
  verb->add_option("-o,--out", args->output, "Folder for capture/, result/ and tracks.csv")
      ->capture_default_str();
  verb->add_option("--species", args->options.species, "Synth species preset")
      ->capture_default_str();
  verb->add_option("--seed", args->options.seed, "Seed of the synthetic tree")
      ->capture_default_str();
  verb->add_option("--duration", args->options.duration_s, "Pull stream length (s)")
      ->capture_default_str();
  verb->add_option("--views", args->options.views, "Static scan views")->capture_default_str();
  verb->add_flag("!--no-render", args->options.render, "No side-by-side frames");
  verb->footer(Examples({"simtree demo --out out/demo",
                         "simtree demo --out out/magnolia --species magnolia --seed 3"}));
  verb->callback([args] {
    const pipeline::DemoResult demo = pipeline::RunDemo(args->output, args->options);
    PrintRunTable(demo.run);
    std::printf("\n%s\n", demo.evaluation.markdown.c_str());
    if (demo.simulated_tracks) {
      std::printf(
          "note: trajectories = the truth with a tracker's errors (the capture has no "
          "pull/init.json to track from)\n");
    }
    std::printf("demo done in %.1f s\nopen %s\n", demo.wall_s, demo.report.string().c_str());
  });
}

}  // namespace simtree::cli
