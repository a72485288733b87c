#include <filesystem>
#include <memory>
#include <optional>

#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/io/capture.h"
#include "simtree/io/image_io.h"
#include "simtree/io/point_cloud_io.h"
#include "simtree/preprocessing/preprocess.h"
#include "simtree/registration/register.h"
#include "simtree/registration/register_extra_view.h"
#include "simtree/registration/registration_report.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace simtree::cli {

void AddPreprocessOptions(CLI::App* verb, preprocessing::PreprocessOptions& options);
void RefuseToReplaceInputs(const fs::path& output, const fs::path& input);

namespace {

// The capture at `input` for --pull-camera; an error when it is not a capture with a pull stream.
Capture CaptureWithPullStream(const fs::path& input) {
  if (!fs::exists(input / "capture.json") && !fs::is_directory(input / "scans")) {
    throw InputError(input.string(), "",
                     "expected a capture folder (scans/, pull/) for --pull-camera");
  }
  Capture capture = OpenCapture(input);
  if (!capture.pull) {
    throw InputError(input.string(), "pull/",
                     "expected a pull-test stream for --pull-camera, found none");
  }
  return capture;
}

struct RegisterArgs {
  std::string input, output, coarse = "key_region_skeleton";
  preprocessing::PreprocessOptions preprocess;
  registration::MultiViewOptions multiview;
  bool open_ring = false, no_icp = false, no_priors = false, pull_camera = false;
  double key_radius = 0.0;
};

void AddRegisterOptions(CLI::App* verb, RegisterArgs& args) {
  verb->add_option("input", args.input,
                   "A capture folder (scans/), the output of `simtree preprocess`, or a folder of "
                   "point-cloud files (one per view, in name order around the tree)")
      ->required()
      ->check(CLI::ExistingDirectory);
  verb->add_option("-o,--out", args.output,
                   "Folder to write: poses.json, merged.ply, pairs.md, pairs.json, "
                   "before_after.png (and pull_camera.json)")
      ->required();
  verb->add_option("--coarse", args.coarse,
                   "What coarse registration aligns (paper Table I): key_region_skeleton, "
                   "key_region, tree_skeleton or entire_tree")
      ->capture_default_str()
      ->check(CLI::IsMember({"key_region_skeleton", "key_region", "tree_skeleton", "entire_tree"}));
  verb->add_option("--span", args.multiview.neighbour_span,
                   "Pair each view with this many next views (2 closes small loops)")
      ->capture_default_str()
      ->check(CLI::Range(1, 10));
  verb->add_flag("--open-ring", args.open_ring,
                 "The views do not go all around the tree (the last is not next to the first)");
  verb->add_option("--anchor", args.multiview.anchor,
                   "Index of the view whose frame is kept (-1: the best connected)")
      ->capture_default_str();
  verb->add_option("--key-radius", args.key_radius,
                   "Key region radius in metres (0: a quarter of the tree's visible height)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_flag("--no-icp", args.no_icp, "Coarse registration only");
  verb->add_flag("--no-priors", args.no_priors,
                 "The paper's SAC-IA and ICP alone: no up, trunk or ground priors");
  verb->add_flag("--pull-camera", args.pull_camera,
                 "Also register the pull stream's first frame (a capture with pull/) like one more "
                 "view: the pull camera in the registration frame, in pull_camera.json");
  AddPreprocessOptions(verb, args.preprocess);
}

// What went wrong, pair by pair and view by view, and what was written.
void LogRegistration(const registration::MultiViewResult& result,
                     const std::optional<registration::ExtraViewResult>& pull,
                     const std::string& output) {
  for (const registration::PairEdge& edge : result.pairs) {
    if (!edge.result.ok()) {
      spdlog::warn("pair {} -> {}: failed: {}", edge.result.source, edge.result.target,
                   edge.result.status);
    } else if (!edge.consistent) {
      spdlog::warn(
          "pair {} -> {}: disagrees with the other pairs by {:.2f} deg, {:.0f} mm; "
          "left out",
          edge.result.source, edge.result.target, edge.rotation_residual_deg,
          1e3 * edge.shift_residual_m);
    }
  }
  for (const registration::ViewRegistration& view : result.views) {
    if (!view.registered()) spdlog::warn("{}: not registered: {}", view.name, view.status);
  }
  if (pull && pull->placed()) {
    spdlog::info("pull camera ({}): {} by {} pair(s), spread {:.2f} deg, {:.0f} mm", pull->name,
                 pull->status, pull->pairs_used, pull->rotation_spread_deg,
                 1e3 * pull->shift_spread_m);
  } else if (pull) {
    spdlog::warn("pull camera ({}): not placed: {}", pull->name, pull->status);
  }
  spdlog::info("registered {} of {} views ({} pairs, {:.1f} s); wrote {}", result.RegisteredCount(),
               result.views.size(), result.pairs.size(), result.seconds, output);
}

void RunRegister(RegisterArgs& args) {
  RefuseToReplaceInputs(args.output, args.input);
  registration::RegistrationViewOptions view_options;
  view_options.coarse_input = registration::ParseCoarseInput(args.coarse);
  view_options.key_region.radius_m = args.key_radius;
  registration::MultiViewOptions& mv = args.multiview;
  mv.closed_ring = !args.open_ring;
  mv.pair.run_icp = !args.no_icp;
  if (args.no_priors) {
    mv.pair.up_prior = mv.pair.center_prior = mv.pair.snap_to_priors = false;
    mv.pair.trunk_axis_weight = mv.pair.ground_weight = 0.0;
  }
  // Every option, and the pull stream asked for, checked before the views are read.
  view_options.Validate();
  mv.Validate();
  const std::optional<Capture> capture =
      args.pull_camera ? std::optional<Capture>(CaptureWithPullStream(args.input)) : std::nullopt;
  const std::vector<registration::RegistrationView> views = registration::PrepareViews(
      preprocessing::LoadViews(args.input, args.preprocess), view_options);
  const registration::MultiViewResult result = registration::RegisterViews(views, mv);
  std::optional<registration::ExtraViewResult> pull;
  if (capture) {
    registration::ExtraViewOptions pull_options;
    pull_options.pair = mv.pair;
    pull = registration::RegisterPullFrame(*capture, views, result, args.preprocess, view_options,
                                           pull_options);
  }

  AtomicDirectory folder(args.output);
  const fs::path dir = folder.path();
  WriteFileAtomically(dir / "poses.json", registration::PosesToJson(result).dump(1) + "\n");
  WriteFileAtomically(dir / "pairs.json", registration::PairsToJson(result).dump(1) + "\n");
  WriteFileAtomically(dir / "pairs.md", registration::PairsMarkdown(result));
  WritePng(registration::BeforeAfterPicture(views, result), dir / "before_after.png");
  if (!result.merged.points_.empty()) WritePointCloud(result.merged, dir / "merged.ply");
  if (pull) {
    WriteFileAtomically(dir / "pull_camera.json",
                        registration::ExtraViewToJson(*pull).dump(1) + "\n");
  }
  folder.Commit();

  LogRegistration(result, pull, args.output);
  if (result.RegisteredCount() < 2 && result.views.size() >= 2) {
    throw InputError(args.input, "",
                     "expected at least two views to register, got " +
                         std::to_string(result.RegisteredCount()) +
                         " (see pairs.md in the output for why)");
  }
}

}  // namespace

void RegisterRegister(CLI::App& app) {
  auto args = std::make_shared<RegisterArgs>();
  CLI::App* verb = app.add_subcommand(
      "register",
      "Register the views of a capture into one cloud (paper III-A): key-region L1-medial "
      "skeletons aligned by SAC-IA, then point-to-plane ICP and a fit onto the branch axes, "
      "tried at the turns about the trunk that overlap best; pairs around the tree, a pose "
      "graph, failed pairs and views reported, never merged");
  AddRegisterOptions(verb, *args);
  verb->footer(Examples(
      {"simtree register scene/ --out reg/", "simtree register scene/ --out reg/ --pull-camera",
       "simtree preprocess scene/ --out clean/ && simtree register clean/ --out reg/",
       "simtree register scene/ --out reg/ --coarse entire_tree --no-priors"}));
  verb->callback([args] { RunRegister(*args); });
}

}  // namespace simtree::cli
