#include <cstdio>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/report/report.h"
#include "verbs.h"

namespace simtree::cli {

void RegisterReport(CLI::App& app) {
  struct Args {
    std::string result, output, javascript_dir;
    double max_mb = 20.0;
    report::ReportOptions options;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "report",
      "Write (or rebuild) the self-contained HTML report of a result folder: stages, views, "
      "registration, static tree, tracking, spectra, branches, the pull-and-release in 3D, "
      "simulation beside the capture, the paper's tables and the scores; opens offline");
  verb->add_option("result", args->result, "Result folder (what `simtree run` writes)")
      ->required()
      ->check(CLI::ExistingDirectory);
  verb->add_option("-o,--out", args->output, "HTML file to write (default: RESULT/report.html)");
  verb->add_option(
      "--javascript-dir", args->javascript_dir,
      fmt::format("Folder with three/ and chart.js/ as the Debian packages libjs-three "
                  "and libjs-chart.js lay them out (default: {})",
                  report::DefaultJavaScriptDir().string()));
  verb->add_flag("--allow-missing-javascript", args->options.allow_missing_javascript,
                 "Write the page without the charts and the 3D view when a library is missing");
  verb->add_option("--max-mb", args->max_mb, "Largest file size in MB (10^6 bytes)")
      ->capture_default_str()
      ->check(CLI::Range(2.0, 1000.0));
  verb->add_option("--render-frames", args->options.render_frames,
                   "Side-by-side frames shown from render/")
      ->capture_default_str();
  verb->footer(Examples({
      "simtree report out/demo/result",
      "simtree report result/ --out /tmp/report.html --max-mb 10",
  }));
  verb->callback([args] {
    report::ReportOptions& options = args->options;
    options.output = args->output;
    options.javascript_dir = args->javascript_dir;
    options.max_bytes = static_cast<int64_t>(args->max_mb * 1e6);
    options.animation_max_bytes = std::min(options.animation_max_bytes, options.max_bytes);
    const report::ReportResult result = report::WriteReport(args->result, options);
    for (const std::string& note : result.notes) spdlog::info("report: {}", note);
    if (result.animation.present) {
      spdlog::info("report: animation {} nodes x {} frames sent as {} x {} ({:.1f} fps): {:.2f} MB",
                   result.animation.nodes, result.animation.frames, result.animation.sent_nodes,
                   result.animation.sent_frames, result.animation.sent_fps,
                   result.animation.bytes / 1e6);
    }
    std::printf("wrote %s (%.2f MB: images %.2f, libraries %.2f, animation %.2f)\n",
                result.path.c_str(), result.bytes / 1e6, result.image_bytes / 1e6,
                result.library_bytes / 1e6, result.animation.bytes / 1e6);
  });
}

}  // namespace simtree::cli
