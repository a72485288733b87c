#include <cstdio>
#include <filesystem>
#include <memory>

#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/eval/eval_run.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace simtree::cli {

// `simtree eval RESULT --gt CAPTURE`: the parent `eval` verb itself, for a run's result folder.
void AddEvalRun(CLI::App& eval) {
  struct Args {
    std::string result, capture;
    eval::RunEvalOptions options;
  };
  auto args = std::make_shared<Args>();
  eval.add_option("result", args->result,
                  "A result folder of `simtree run`: every stage against the truth, written to "
                  "RESULT/eval/eval.json and eval.md")
      ->check(CLI::ExistingDirectory);
  eval.add_option("--gt", args->capture, "The synth capture the run was made from (its gt/)")
      ->check(CLI::ExistingDirectory);
  eval.add_option("--window", args->options.chain_window_s,
                  "Seconds after the release the simulated held-out markers are scored over")
      ->capture_default_str();
  eval.footer(Examples({"simtree eval result/ --gt capture/",
                        "simtree eval identification materials.json --gt capture/"}));
  eval.callback([args, &eval] {
    if (!eval.get_subcommands().empty()) return;  // a sub-command ran
    if (args->result.empty() || args->capture.empty()) {
      throw CLI::RequiredError("RESULT and --gt CAPTURE (or a sub-command)");
    }
    const eval::RunEvaluation ev = eval::EvaluateRun(args->result, args->capture, args->options);
    eval::WriteRunEvaluation(ev, fs::path(args->result) / "eval");
    std::printf("%s", ev.markdown.c_str());
    spdlog::info("wrote {}", (fs::path(args->result) / "eval" / "eval.json").string());
  });
}

}  // namespace simtree::cli
