#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli_common.h"
#include "simtree/capture_check/capture_check.h"
#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/io/intrinsics_file.h"
#include "simtree/io/recording_layout.h"
#include "verbs.h"

namespace simtree::cli {

namespace {

// A capture folder, or what is no recording either (a missing path, an empty folder): checked as a
// capture folder, whose errors say what one holds.
bool CheckAsCaptureFolder(const std::filesystem::path& p) {
  if (std::filesystem::exists(p / "capture.json") || std::filesystem::exists(p / "scans") ||
      std::filesystem::exists(p / "pull")) {
    return true;
  }
  try {
    DetectLayout(p);
    return false;
  } catch (const InputError&) {
    return true;
  }
}

}  // namespace

void RegisterCaptureCheck(CLI::App& app) {
  struct Args {
    std::vector<std::string> inputs;
    std::string pull, layout = "auto", intrinsics;
    bool json = false;
    capture_check::CaptureCheckOptions options;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "capture-check",
      "What to fix in a capture before the long run (a capture folder, or recordings as "
      "capture-from takes them): scan views (depth on the tree, "
      "distance, blur, exposure, coverage around the tree by a quick registration), the pull "
      "stream (frame rate, length, dropped frames) and its first frame (the same, and the tape "
      "markers: found, how many pixels wide). Each check: value, limits, ok/warn/fail and a fix "
      "(docs/capturing.md). Exits 1 when a check fails, 0 otherwise");
  verb->add_option("inputs", args->inputs,
                   "A capture folder, or scan recordings in any layout capture-from reads (.mkv, "
                   ".bag, TUM, Open3D folders), checked through a temporary capture folder");
  verb->add_option("--pull", args->pull, "The pull test's recording (with recordings)")
      ->check(CLI::ExistingPath);
  verb->add_option("--layout", args->layout, "The recordings' layout, as capture-from's")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "mkv", "bag", "tum", "open3d"}));
  verb->add_option("--intrinsics", args->intrinsics,
                   "Camera of TUM or Open3D recordings, as capture-from's")
      ->check(CLI::ExistingFile);
  verb->add_flag("--json", args->json,
                 "Print the checks as JSON (simtree.capture_check, docs/formats.md) instead of "
                 "the table");
  verb->add_option("--color", args->options.tape_color,
                   "The tape's colour, as track --color: auto, red, green, blue, yellow, orange "
                   "or #rrggbb")
      ->capture_default_str();
  verb->add_flag(
      "--no-register", [args](int64_t) { args->options.register_views = false; },
      "Skip the view coverage (it registers the views: most of the check's time)");
  verb->footer(Examples({"simtree capture-check capture/",
                         "simtree capture-check capture/ --json > check.json",
                         "simtree capture-check north.mkv east.mkv south.mkv west.mkv --pull "
                         "pull.mkv   # recordings, before capture-from"}));
  verb->callback([args] {
    if (args->inputs.empty() && args->pull.empty()) {
      throw OptionError("inputs", "expected a capture folder, scan recordings or --pull");
    }
    const bool folder = args->pull.empty() && args->inputs.size() == 1 &&
                        CheckAsCaptureFolder(args->inputs.front());
    capture_check::CaptureCheckResult result;
    if (folder) {
      result = capture_check::CheckCapture(args->inputs.front(), args->options);
    } else {
      CaptureFromOptions from;
      for (const std::string& s : args->inputs) from.scans.emplace_back(s);
      if (!args->pull.empty()) from.pull = args->pull;
      from.layout = ParseLayout(args->layout);
      if (!args->intrinsics.empty()) {
        from.sequence.intrinsics = ReadIntrinsicsFile(args->intrinsics);
      }
      result = capture_check::CheckRecordings(from, args->options);
    }
    const std::string text = args->json ? capture_check::ToJson(result).dump(2) + "\n"
                                        : capture_check::FormatTable(result);
    std::fputs(text.c_str(), stdout);
    std::fflush(stdout);
    if (result.Worst() == capture_check::Status::kFail) throw CLI::RuntimeError(1);
  });
}

}  // namespace simtree::cli
