#include <filesystem>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_common.h"
#include "simtree/core/atomic_file.h"
#include "simtree/core/atomic_file_set.h"
#include "simtree/core/tree_file.h"
#include "simtree/core/tube_mesh.h"
#include "simtree/eval/reconstruction_metrics.h"
#include "simtree/io/mesh_io.h"
#include "simtree/io/point_cloud_io.h"
#include "simtree/reconstruction/reconstruct.h"
#include "simtree/reconstruction/reconstruction_plot.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace simtree::cli {
namespace {

struct ReconstructArgs {
  std::string input, output, mesh, picture;
  reconstruction::ReconstructionOptions options;
  bool no_fit_score = false;
};

void AddReconstructOptions(CLI::App* verb, ReconstructArgs& args) {
  verb->add_option(
          "cloud", args.input,
          "Point cloud: .xyz/.txt/.pts (x y z per line), .ply, .pcd, .las (LAZ: decompress first)")
      ->required()
      ->check(CLI::ExistingFile);
  verb->add_option("-o,--out", args.output, "Tree to write: .json (simtree) or .txt (demo format)")
      ->required();
  verb->add_option("--mesh", args.mesh, "Also write the model as tubes: .ply or .obj");
  verb->add_option("--picture", args.picture,
                   "Also write a PNG of the model over the points (front and side views)");
  verb->add_option("--scale", args.options.preparation.scale,
                   "Multiply the cloud's coordinates by this (0.001 for millimetres)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  verb->add_option("--voxel", args.options.scale.voxel_m,
                   "Working resolution in metres (0: from the measured point spacing)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_option("--max-gap", args.options.scale.max_gap_m,
                   "Longest occlusion gap bridged, metres (0: from the point spacing, >= 0.3)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  verb->add_option("--pipe-exponent", args.options.radii.pipe_exponent,
                   "n of the pipe model r_parent^n = sum r_child^n")
      ->capture_default_str()
      ->check(CLI::Range(1.5, 4.0));
  verb->add_flag("!--keep-ground", args.options.remove_ground,
                 "Do not look for and remove a ground plane");
  verb->add_option("--seed", args.options.seed, "Seed of the random choices (MSAC, RANSAC)")
      ->capture_default_str();
  verb->add_flag("--no-fit-score", args.no_fit_score,
                 "Skip measuring the points' distance to the model surface");
}

std::string LevelCounts(const Tree& tree) {
  std::string out;
  const std::vector<int> counts = eval::BranchCountsByLevel(tree);
  for (size_t l = 0; l < counts.size(); ++l)
    out += fmt::format("{}{}: {}", l ? ", " : "", l, counts[l]);
  return out;
}

// Logs what the reconstruction measured and built; returns the picture's caption.
std::vector<std::string> LogSummary(const std::string& source,
                                    const reconstruction::ReconstructionResult& result,
                                    const Tree& tree) {
  const reconstruction::ReconstructionScale& p = result.parameters;
  spdlog::info(
      "{}: {} points (spacing {:.1f} mm, roughness {:.1f} mm), {} working points at "
      "{:.1f} mm",
      source, result.input_points, 1e3 * result.measured.spacing_m,
      1e3 * result.measured.roughness_m, result.working_points, 1e3 * p.voxel_m);
  if (result.ground.found) {
    spdlog::info("ground plane removed ({} points)", result.ground.ground_points);
  }
  const reconstruction::TrunkFit& trunk = result.trunk;
  if (trunk.found) {
    spdlog::info(
        "trunk: MSAC cylinder radius {:.3f} m over {:.2f} m, {} inliers ({:.0f}%), "
        "RMS {:.1f} mm, slices {}",
        trunk.cylinder.radius, trunk.length_m, trunk.inliers, 100 * trunk.inlier_share,
        1e3 * trunk.rms_m, trunk.slices_agree ? "agree" : "disagree");
  }
  spdlog::info(
      "skeleton: {} nodes from {} attraction points (step {:.1f} mm), {} bridges, "
      "{} twigs pruned",
      result.skeleton.size(), result.attraction_points, 1e3 * p.step_m,
      result.colonization.bridges + result.graph_bridges, result.pruning.twigs_removed);
  double wood = 0;
  for (const Branch& b : tree.branches) wood += b.Length();
  spdlog::info("tree: {} branches (by level {}), {:.2f} m of wood; {:.3f} s", tree.size(),
               LevelCounts(tree), wood, result.times.total_s);
  std::vector<std::string> caption = {
      fmt::format("{} points, spacing {:.1f} mm; {} branches (by level {}); reconstructed in "
                  "{:.2f} s",
                  result.input_points, 1e3 * result.measured.spacing_m, tree.size(),
                  LevelCounts(tree), result.times.total_s)};
  if (trunk.found) {
    caption.push_back(fmt::format("trunk: MSAC cylinder r = {:.1f} cm, slices {}",
                                  100 * trunk.cylinder.radius,
                                  trunk.slices_agree ? "agree" : "disagree"));
  }
  return caption;
}

// The tree, mesh and picture appear together or not at all: a failure (or Ctrl-C) while any of
// them is made leaves every target as it was.
void RunReconstruct(const ReconstructArgs& args) {
  RefuseToOverwriteInputs(args.output, {args.input});
  if (!args.mesh.empty()) RefuseToOverwriteInputs(args.mesh, {args.input});
  if (!args.picture.empty()) RefuseToOverwriteInputs(args.picture, {args.input});
  CheckTreeFilePath(args.output);
  if (!args.mesh.empty()) CheckMeshPath(args.mesh);
  AtomicFileSet outputs;
  const fs::path tree_file = outputs.Stage(args.output);
  const fs::path mesh_file = args.mesh.empty() ? fs::path() : outputs.Stage(args.mesh);
  const fs::path picture_file = args.picture.empty() ? fs::path() : outputs.Stage(args.picture);
  PointCloudReadReport read;
  const open3d::geometry::PointCloud cloud = ReadPointCloud(args.input, &read);
  const std::string source = fs::path(args.input).filename().string();
  const reconstruction::ReconstructionResult result =
      reconstruction::ReconstructTree(cloud.points_, args.input, args.options);
  Tree tree = result.tree;
  tree.metadata.source = "reconstructed from " + source;
  WriteTreeFile(tree, tree_file);
  std::vector<std::string> caption = LogSummary(source, result, tree);
  if (!args.no_fit_score) {
    const eval::CloudFitScores fit = eval::ScoreAgainstCloud(tree, cloud.points_);
    spdlog::info("fit: {}", eval::FormatCloudFit(fit));
    caption.push_back(fmt::format("points to model surface: mean {:.1f} mm, {:.1f}% within 2 cm",
                                  1e3 * fit.mean_distance_m, 100 * fit.share_within));
  }
  TriangleMesh mesh;
  if (!args.mesh.empty()) {
    mesh = BuildTubeMesh(tree);
    MeshWriteOptions write;
    write.colour_by_level_of = &tree;
    WriteMesh(mesh, mesh_file, write);
  }
  if (!args.picture.empty()) {
    reconstruction::ReconstructionPlotOptions plot;
    plot.title = "simtree reconstruct " + source;
    plot.caption = caption;
    reconstruction::WriteReconstructionPlot(tree, cloud.points_, picture_file, plot);
  }
  outputs.Commit();
  spdlog::info("wrote {}", args.output);
  if (!args.mesh.empty()) spdlog::info("wrote {} ({} triangles)", args.mesh, mesh.triangle_count());
  if (!args.picture.empty()) spdlog::info("wrote {}", args.picture);
}

}  // namespace

void RegisterReconstruct(CLI::App& app) {
  auto args = std::make_shared<ReconstructArgs>();
  CLI::App* verb = app.add_subcommand(
      "reconstruct",
      "Static tree from a registered cloud (paper III-B): improved space colonization, MSAC "
      "trunk cylinder, allometric radii, branch hierarchy");
  AddReconstructOptions(verb, *args);
  verb->footer(Examples({
      "simtree reconstruct tree1.xyz --out tree1.json --mesh tree1.ply --picture tree1.png",
      "simtree reconstruct scan_mm.ply --scale 0.001 --out tree.json",
  }));
  verb->callback([args] { RunReconstruct(*args); });
}

}  // namespace simtree::cli
