#include <filesystem>
#include <memory>
#include <string>

#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/io/capture.h"
#include "simtree/io/capture_export.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace simtree::cli {

void RegisterCaptureExport(CLI::App& app) {
  struct Args {
    std::string input, output, color = "mjpg";
    bool pull_only = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "capture-export",
      "A capture folder to Azure Kinect recordings (.mkv as k4arecorder writes them): "
      "view_XX.mkv per scan view and pull.mkv, with a calibration of the capture's camera (no "
      "distortion) and a virtual 640x576 depth camera at the same place; `capture-from` reads "
      "them back. The colour camera must have a colour mode's shape (synth --color-size "
      "1280x720)");
  verb->add_option("capture", args->input, "Capture folder")
      ->required()
      ->check(CLI::ExistingDirectory);
  verb->add_option("-o,--out", args->output, "Folder to write the recordings into")->required();
  verb->add_option("--color", args->color, "Colour track format")
      ->capture_default_str()
      ->check(CLI::IsMember({"mjpg", "nv12", "yuy2", "bgra"}));
  verb->add_flag("--pull-only", args->pull_only,
                 "Only pull.mkv (synth's scan views are registered to the depth camera, 640x576, "
                 "which is no colour mode's shape)");
  verb->footer(
      Examples({"simtree synth --color-size 1280x720 --out scene/ && simtree "
                "capture-export scene/ --out rec/ --pull-only",
                "simtree capture-from --pull rec/pull.mkv --out back/",
                "simtree capture-export my_capture/ --out rec/ --color nv12"}));
  verb->callback([args] {
    RefuseToOverwriteInputs(args->output, {args->input});
    CaptureExportOptions options;
    options.color_format = args->color == "nv12"   ? AzureColorFormat::kNv12
                           : args->color == "yuy2" ? AzureColorFormat::kYuy2
                           : args->color == "bgra" ? AzureColorFormat::kBgra
                                                   : AzureColorFormat::kMjpeg;
    options.pull_only = args->pull_only;
    const Capture capture = OpenCapture(args->input);
    AtomicDirectory folder(args->output);
    const CaptureExportResult result = ExportCapture(capture, folder.path(), options);
    folder.Commit();
    spdlog::info("wrote {}: {} scan recordings, pull.mkv with {} frames", args->output,
                 result.scans.size(), result.pull_frames);
  });
}

}  // namespace simtree::cli
