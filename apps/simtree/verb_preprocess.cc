#include <filesystem>
#include <memory>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/preprocessing/preprocess.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace simtree::cli {

// Options shared by `preprocess` and `register` (which preprocesses a capture itself).
// RefuseToOverwriteInputs, and also an existing folder inside the input (`--out capture/scans`
// would replace the views themselves).
void RefuseToReplaceInputs(const fs::path& output, const fs::path& input) {
  RefuseToOverwriteInputs(output, {input});
  std::error_code ec;
  const fs::path out = fs::weakly_canonical(output, ec);
  const fs::path in = fs::weakly_canonical(input, ec);
  const fs::path rel = out.lexically_relative(in);
  const bool inside = !rel.empty() && rel.native().rfind("..", 0) != 0;
  if (inside && fs::exists(out)) {
    throw InputError(output.string(), "",
                     fmt::format("refusing to replace a folder inside the input {}; choose "
                                 "another output",
                                 input.string()));
  }
}

void AddPreprocessOptions(CLI::App* verb, preprocessing::PreprocessOptions& options) {
  verb->add_option("--voxel", options.voxel_size_m,
                   "Voxel grid size in metres (0: --voxel-factor times the measured point spacing)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_option("--voxel-factor", options.voxel_spacing_factor,
                   "Voxel grid size in point spacings when --voxel is 0 (the paper: 2-3)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  verb->add_flag("!--keep-ground", options.remove_ground, "Do not remove the ground plane");
  verb->add_option("--outlier-neighbors", options.outlier_neighbors,
                   "Statistical outlier filter: neighbours per point (0: off)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_option("--outlier-std", options.outlier_std_ratio,
                   "Statistical outlier filter: standard deviations allowed")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  verb->add_flag("!--keep-clusters", options.keep_tree_cluster,
                 "Keep every cluster, not only the tree's");
  verb->add_option("--seed", options.seed, "Seed of the random choices")->capture_default_str();
}

void RegisterPreprocess(CLI::App& app) {
  struct Args {
    std::string input, output;
    preprocessing::PreprocessOptions preprocess;
  };
  auto args = std::make_shared<Args>();
  CLI::App* verb = app.add_subcommand(
      "preprocess",
      "RGB-D views (a capture folder) or point clouds to one clean tree cloud per view (paper "
      "III-A): ground plane removal, statistical outlier removal, voxel grid, the tree's cluster");
  verb->add_option("input", args->input,
                   "A capture folder (scans/view_XX/{color,depth}.png, intrinsics.json) or a "
                   "folder of point-cloud files (.ply, .pcd, .xyz, .las), one per view")
      ->required()
      ->check(CLI::ExistingDirectory);
  verb->add_option("-o,--out", args->output,
                   "Folder to write: <view>.ply per view (camera frame) and preprocess.json")
      ->required();
  AddPreprocessOptions(verb, args->preprocess);
  verb->footer(Examples({"simtree preprocess scene/ --out clean/",
                         "simtree preprocess scene/ --out clean/ --voxel 0.01 --keep-clusters"}));
  verb->callback([args] {
    RefuseToReplaceInputs(args->output, args->input);
    const auto views = preprocessing::LoadViews(args->input, args->preprocess);
    AtomicDirectory folder(args->output);
    preprocessing::WritePreprocessedViews(views, folder.path());
    folder.Commit();
    int failed = 0;
    for (const preprocessing::PreprocessedView& view : views) {
      if (!view.result) {
        ++failed;
        spdlog::warn("{}: not usable: {}", view.name, view.failure);
        continue;
      }
      const preprocessing::PreprocessResult& r = *view.result;
      spdlog::info(
          "{}: {} points -> {} tree points (ground {}, outliers {}, voxel {:.1f} mm = {:.1f} x "
          "spacing {:.1f} mm removed {:.0f}%, off the tree {}) in {:.2f} s",
          view.name, r.input_points, r.cloud.points_.size(), r.ground_points, r.outlier_points,
          1e3 * r.voxel_size_m, r.voxel_size_m / r.point_spacing_m, 1e3 * r.point_spacing_m,
          100 * r.DownsampleRemovedShare(), r.off_tree_points, r.seconds);
    }
    if (failed == static_cast<int>(views.size())) {
      throw InputError(args->input, "", "expected at least one usable view, every view failed");
    }
    spdlog::info("wrote {} ({} of {} views usable)", args->output, views.size() - failed,
                 views.size());
  });
}

}  // namespace simtree::cli
