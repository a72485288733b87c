// The static tree's stages: preprocess, register (with the pull camera), reconstruct.

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/tree_json.h"
#include "simtree/core/tube_mesh.h"
#include "simtree/io/image_io.h"
#include "simtree/io/mesh_io.h"
#include "simtree/io/point_cloud_io.h"
#include "simtree/pipeline/detail/stage_functions.h"
#include "simtree/pipeline/run.h"
#include "simtree/preprocessing/preprocess.h"
#include "simtree/reconstruction/reconstruct.h"
#include "simtree/reconstruction/reconstruction_plot.h"
#include "simtree/registration/register.h"
#include "simtree/registration/register_extra_view.h"
#include "simtree/registration/registration_report.h"

namespace simtree::pipeline::detail {

std::string RunPreprocessStage(const StageContext& context) {
  preprocessing::PreprocessOptions options;
  options.seed = context.options.seed;
  const std::vector<preprocessing::PreprocessedView> views =
      preprocessing::PreprocessCaptureViews(context.capture, options);
  preprocessing::WritePreprocessedViews(views, context.out_dir);
  int usable = 0;
  for (const preprocessing::PreprocessedView& view : views) {
    if (view.result) {
      ++usable;
    } else {
      spdlog::warn("preprocess: {}: not usable: {}", view.name, view.failure);
    }
  }
  if (usable == 0) {
    throw InputError(context.capture_dir.string(), "scans/",
                     "expected at least one usable view, every view failed (see "
                     "preprocess.json)");
  }
  return fmt::format("{} of {} views usable", usable, views.size());
}

std::string RunRegisterStage(const StageContext& context) {
  preprocessing::PreprocessOptions preprocess;
  preprocess.seed = context.options.seed;
  const registration::RegistrationViewOptions view_options;
  const registration::MultiViewOptions multiview;
  const std::vector<registration::RegistrationView> views = registration::PrepareViews(
      preprocessing::ReadPreprocessedViews(context.Result("preprocess")), view_options);
  const registration::MultiViewResult result = registration::RegisterViews(views, multiview);
  registration::ExtraViewOptions pull_options;
  pull_options.pair = multiview.pair;
  const registration::ExtraViewResult pull = registration::RegisterPullFrame(
      context.capture, views, result, preprocess, view_options, pull_options);

  const std::filesystem::path& dir = context.out_dir;
  WriteFileAtomically(dir / "poses.json", registration::PosesToJson(result).dump(1) + "\n");
  WriteFileAtomically(dir / "pairs.json", registration::PairsToJson(result).dump(1) + "\n");
  WriteFileAtomically(dir / "pairs.md", registration::PairsMarkdown(result));
  WritePng(registration::BeforeAfterPicture(views, result), dir / "before_after.png");
  if (!result.merged.points_.empty()) WritePointCloud(result.merged, dir / "merged.ply");
  WriteFileAtomically(dir / "pull_camera.json", registration::ExtraViewToJson(pull).dump(1) + "\n");
  if (result.RegisteredCount() < 2 && result.views.size() >= 2) {
    throw InputError(context.capture_dir.string(), "scans/",
                     fmt::format("expected at least two views to register, got {} (see "
                                 "register/pairs.md)",
                                 result.RegisteredCount()));
  }
  if (!pull.placed()) {
    throw InputError(context.capture_dir.string(), "pull/",
                     "the pull camera could not be placed among the scans (" + pull.status +
                         "): the tracked markers cannot be put on the tree");
  }
  return fmt::format("{} of {} views registered; pull camera {} ({} pairs, {:.0f} mm spread)",
                     result.RegisteredCount(), result.views.size(), pull.status, pull.pairs_used,
                     1e3 * pull.shift_spread_m);
}

std::string RunReconstructStage(const StageContext& context) {
  const std::filesystem::path cloud_path = context.Result("register/merged.ply");
  const open3d::geometry::PointCloud cloud = ReadPointCloud(cloud_path);
  reconstruction::ReconstructionOptions options;
  options.seed = context.options.seed;
  const reconstruction::ReconstructionResult result =
      reconstruction::ReconstructTree(cloud.points_, cloud_path.string(), options);
  Tree tree = result.tree;
  tree.metadata.source = "reconstructed from register/merged.ply";
  const std::filesystem::path& dir = context.out_dir;
  WriteTreeJson(tree, dir / "static.json");
  MeshWriteOptions mesh;
  mesh.colour_by_level_of = &tree;
  WriteMesh(BuildTubeMesh(tree), dir / "static.ply", mesh);
  double wood = 0.0;
  for (const Branch& b : tree.branches) wood += b.Length();
  const std::string summary = fmt::format("{} branches, {:.2f} m of wood from {} points",
                                          tree.size(), wood, result.input_points);
  reconstruction::ReconstructionPlotOptions plot;
  plot.title = "simtree run: reconstruct";
  plot.caption = {summary};
  reconstruction::WriteReconstructionPlot(tree, cloud.points_, dir / "picture.png", plot);
  return summary;
}

}  // namespace simtree::pipeline::detail
