#include <cstdio>
#include <memory>
#include <string>

#include "cli_common.h"
#include "simtree/capture_check/capture_check.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterCaptureCheck(CLI::App& app) {
  struct Args {
    std::string capture;
    bool json = false;
    capture_check::CaptureCheckOptions options;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "capture-check",
      "What to fix in a capture folder before the long run: scan views (depth on the tree, "
      "distance, sharpness, exposure, coverage around the tree by a quick registration), the pull "
      "stream (frame rate, length, dropped frames) and its first frame (the same, and the tape "
      "markers: found, how many pixels wide). Each check: value, limits, ok/warn/fail and a fix "
      "(docs/capturing.md). Exits 1 when a check fails, 0 otherwise");
  verb->add_option("capture", args->capture, "Capture folder (recordings: capture-from first)")
      ->required();
  verb->add_flag("--json", args->json,
                 "Print the checks as JSON (simtree.capture_check, docs/formats.md) instead of "
                 "the table");
  verb->add_option("--color", args->options.tape_color,
                   "The tape's colour, as track --color: auto, red, green, blue, yellow, orange "
                   "or #rrggbb")
      ->capture_default_str();
  verb->add_flag(
      "--no-register", [args](int64_t) { args->options.register_views = false; },
      "Skip the view coverage (it registers the views: a few seconds a pair)");
  verb->footer(Examples({"simtree capture-check capture/",
                         "simtree capture-check capture/ --json > check.json",
                         "simtree capture-from scans/*.mkv --pull pull.mkv --out capture/ && "
                         "simtree capture-check capture/"}));
  verb->callback([args] {
    const capture_check::CaptureCheckResult result =
        capture_check::CheckCapture(args->capture, args->options);
    const std::string text = args->json ? capture_check::ToJson(result).dump(2) + "\n"
                                        : capture_check::FormatTable(result);
    std::fputs(text.c_str(), stdout);
    std::fflush(stdout);
    if (result.Worst() == capture_check::Status::kFail) throw CLI::RuntimeError(1);
  });
}

}  // namespace simtree::cli
