#include <filesystem>
#include <memory>

#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/io/image_io.h"
#include "simtree/io/point_cloud_io.h"
#include "simtree/preprocessing/preprocess.h"
#include "simtree/registration/register.h"
#include "simtree/registration/registration_report.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace simtree::cli {

void AddPreprocessOptions(CLI::App* verb, preprocessing::PreprocessOptions& options);
void RefuseToReplaceInputs(const fs::path& output, const fs::path& input);

void RegisterRegister(CLI::App& app) {
  struct Args {
    std::string input, output, coarse = "key_region_skeleton";
    preprocessing::PreprocessOptions preprocess;
    registration::MultiViewOptions multiview;
    bool open_ring = false, no_icp = false, no_priors = false;
    double key_radius = 0.0;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "register",
      "Register the views of a capture into one cloud (paper III-A): key-region L1-medial "
      "skeletons aligned by SAC-IA, then point-to-plane ICP and a shift onto the branch axes, "
      "tried at the turns about the trunk that overlap best; pairs "
      "around the tree, a pose graph, failed pairs and views reported, never merged");
  verb->add_option("input", args->input,
                   "A capture folder (scans/), the output of `simtree preprocess`, or a folder of "
                   "point-cloud files (one per view, in name order around the tree)")
      ->required()
      ->check(CLI::ExistingDirectory);
  verb->add_option("-o,--out", args->output,
                   "Folder to write: poses.json, merged.ply, pairs.md, pairs.json, "
                   "before_after.png")
      ->required();
  verb->add_option("--coarse", args->coarse,
                   "What coarse registration aligns (paper Table I): key_region_skeleton, "
                   "key_region, tree_skeleton or entire_tree")
      ->capture_default_str()
      ->check(CLI::IsMember({"key_region_skeleton", "key_region", "tree_skeleton", "entire_tree"}));
  verb->add_option("--span", args->multiview.neighbour_span,
                   "Pair each view with this many next views (2 closes small loops)")
      ->capture_default_str()
      ->check(CLI::Range(1, 10));
  verb->add_flag("--open-ring", args->open_ring,
                 "The views do not go all around the tree (the last is not next to the first)");
  verb->add_option("--anchor", args->multiview.anchor,
                   "Index of the view whose frame is kept (-1: the best connected)")
      ->capture_default_str();
  verb->add_option("--key-radius", args->key_radius,
                   "Key region radius in metres (0: a quarter of the tree's visible height)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_flag("--no-icp", args->no_icp, "Coarse registration only");
  verb->add_flag("--no-priors", args->no_priors,
                 "The paper's SAC-IA and ICP alone: no up, trunk or ground priors");
  AddPreprocessOptions(verb, args->preprocess);
  verb->footer(
      Examples({"simtree register scene/ --out reg/",
                "simtree preprocess scene/ --out clean/ && simtree register clean/ --out reg/",
                "simtree register scene/ --out reg/ --coarse entire_tree --no-priors"}));
  verb->callback([args] {
    RefuseToReplaceInputs(args->output, args->input);
    registration::RegistrationViewOptions view_options;
    view_options.coarse_input = registration::ParseCoarseInput(args->coarse);
    view_options.key_region.radius_m = args->key_radius;
    registration::MultiViewOptions& mv = args->multiview;
    mv.closed_ring = !args->open_ring;
    mv.pair.run_icp = !args->no_icp;
    if (args->no_priors) {
      mv.pair.up_prior = mv.pair.center_prior = mv.pair.snap_to_priors = false;
      mv.pair.trunk_axis_weight = mv.pair.ground_weight = 0.0;
    }
    // Every option checked before the views are read.
    view_options.Validate();
    mv.Validate();
    const std::vector<registration::RegistrationView> views = registration::PrepareViews(
        preprocessing::LoadViews(args->input, args->preprocess), view_options);
    const registration::MultiViewResult result = registration::RegisterViews(views, mv);

    AtomicDirectory folder(args->output);
    const fs::path dir = folder.path();
    WriteFileAtomically(dir / "poses.json", registration::PosesToJson(result).dump(1) + "\n");
    WriteFileAtomically(dir / "pairs.json", registration::PairsToJson(result).dump(1) + "\n");
    WriteFileAtomically(dir / "pairs.md", registration::PairsMarkdown(result));
    WritePng(registration::BeforeAfterPicture(views, result), dir / "before_after.png");
    if (!result.merged.points_.empty()) WritePointCloud(result.merged, dir / "merged.ply");
    folder.Commit();

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
    spdlog::info("registered {} of {} views ({} pairs, {:.1f} s); wrote {}",
                 result.RegisteredCount(), result.views.size(), result.pairs.size(), result.seconds,
                 args->output);
    if (result.RegisteredCount() < 2 && result.views.size() >= 2) {
      throw InputError(args->input, "",
                       "expected at least two views to register, got " +
                           std::to_string(result.RegisteredCount()) +
                           " (see pairs.md in the output for why)");
    }
  });
}

}  // namespace simtree::cli
