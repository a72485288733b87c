#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "cli_common.h"
#include "simtree/pipeline/run.h"
#include "verbs.h"

namespace simtree::cli {

// The stages' table `run` and `demo` print at the end.
void PrintRunTable(const pipeline::RunResult& result) {
  std::printf("%-12s %-8s %8s  %s\n", "stage", "status", "wall s", "summary");
  for (const pipeline::StageRecord& s : result.stages) {
    const std::string status = s.reused ? "reused" : s.status;
    std::printf("%-12s %-8s %8.1f  %s\n", s.name.c_str(), status.c_str(), s.wall_s,
                s.summary.c_str());
  }
  std::printf("%d stages ran, %d reused, %.1f s; run.json in %s\n", result.ran, result.reused,
              result.wall_s, result.result_dir.string().c_str());
  if (!result.report.empty()) std::printf("report: %s\n", result.report.string().c_str());
}

void AddRunOptions(CLI::App* verb, pipeline::RunOptions& options) {
  const std::string stages = fmt::format("{}", fmt::join(pipeline::StageNames(), ", "));
  verb->add_option("--tracks", options.tracks,
                   "Marker trajectories (trajectories.csv, pull camera frame) to use instead of "
                   "tracking the pull stream")
      ->check(CLI::ExistingFile);
  verb->add_option("--from", options.from, "Redo this stage and every later one (" + stages + ")")
      ->check(CLI::IsMember(pipeline::StageNames()));
  verb->add_option("--until", options.until, "Stop after this stage")
      ->check(CLI::IsMember(pipeline::StageNames()));
  verb->add_flag("--force", options.force, "Redo every stage");
  verb->add_option("--held-out", options.held_out_markers,
                   "Leaf markers kept from identification, to score the simulation on markers "
                   "it never saw (`simtree eval RESULT --gt CAPTURE`)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_flag("!--no-render", options.render,
                 "Do not draw the simulation beside the capture's frames");
  verb->add_option("--render-width", options.render_width,
                   "Width in pixels of the simulated half of the side-by-side frames")
      ->capture_default_str();
  verb->add_option("--seed", options.seed, "Seed of the stages' random choices")
      ->capture_default_str();
}

void RegisterRun(CLI::App& app) {
  struct Args {
    std::string capture, output;
    pipeline::RunOptions options;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "run",
      "The whole pipeline on a capture folder: preprocess, register (with the pull camera), "
      "reconstruct, track, identify, build, simulate (the capture's pull, replayed), render, "
      "report. One folder per stage under --out, run.json says what ran; a second run reuses "
      "every stage whose inputs and options did not change. Never reads the capture's gt/.");
  verb->add_option("capture", args->capture,
                   "Capture folder: scans/view_XX/{color,depth}.png + intrinsics.json, "
                   "pull/frames.csv + frames + markers.json (docs/formats.md)")
      ->required()
      ->check(CLI::ExistingDirectory);
  verb->add_option("-o,--out", args->output,
                   "Result folder: preprocess/ register/ reconstruct/ track/ identify/ build/ "
                   "simulate/ render/, run.json, report.html")
      ->required();
  AddRunOptions(verb, args->options);
  verb->footer(Examples({
      "simtree run capture/ --out result/ --tracks tracks.csv",
      "simtree run capture/ --out result/ --tracks tracks.csv --from identify",
      "simtree run capture/ --out result/ --tracks tracks.csv --until reconstruct",
      "simtree eval result/ --gt capture/   # a synth capture: every stage against the truth",
  }));
  verb->callback(
      [args] { PrintRunTable(pipeline::Run(args->capture, args->output, args->options)); });
}

}  // namespace simtree::cli
