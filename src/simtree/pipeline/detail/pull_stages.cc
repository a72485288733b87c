// The pull test's stages: track (or the trajectories given), identify (markers placed on the
// reconstructed tree, some leaf markers held out).

#include <algorithm>
#include <set>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/core/tree_json.h"
#include "simtree/identification/identify.h"
#include "simtree/identification/marker_assignment.h"
#include "simtree/identification/materials_file.h"
#include "simtree/io/trajectories.h"
#include "simtree/pipeline/detail/placements.h"
#include "simtree/pipeline/detail/stage_functions.h"
#include "simtree/pipeline/detail/tracking_stage.h"
#include "simtree/pipeline/run.h"
#include "simtree/registration/registration_report.h"

namespace fs = std::filesystem;

namespace simtree::pipeline::detail {

std::string RunTrackStage(const StageContext& context) {
  if (context.options.tracks.empty()) return TrackPullStream(context);
  const Trajectories tracks = ReadTrajectoriesCsv(context.options.tracks);
  WriteTrajectoriesCsv(tracks, context.out_dir / "trajectories.csv");
  return fmt::format("{} markers over {} frames, given ({})", tracks.marker_count(),
                     tracks.frame_count(), context.options.tracks.filename().string());
}

namespace {

// Up to `count` leaf markers (no marker links to them, not the root) with a placement, evenly
// spread over their ids.
std::vector<int> ChooseHeldOut(const std::vector<MarkerLink>& markers, int count) {
  std::set<int> parents;
  for (const MarkerLink& m : markers) parents.insert(m.parent);
  std::vector<int> leaves;
  for (const MarkerLink& m : markers) {
    if (m.parent >= 0 && !parents.count(m.id) && m.branch) leaves.push_back(m.id);
  }
  std::sort(leaves.begin(), leaves.end());
  std::vector<int> chosen;
  const int n = static_cast<int>(leaves.size());
  // Keep at least two leaves for identification.
  const int take = std::max(0, std::min(count, n - 2));
  for (int i = 0; i < take; ++i) chosen.push_back(leaves[(2 * i + 1) * n / (2 * take)]);
  return chosen;
}

Trajectories WithoutMarkers(Trajectories tracks, const std::vector<int>& ids) {
  std::erase_if(tracks.tracks, [&](const MarkerTrack& t) {
    return std::find(ids.begin(), ids.end(), t.marker) != ids.end();
  });
  return tracks;
}

}  // namespace

std::string RunIdentifyStage(const StageContext& context) {
  const Trajectories tracks = ReadTrajectoriesCsv(context.Result("track/trajectories.csv"));
  std::vector<MarkerLink> listed = context.capture.pull->markers;
  // Branch ids of markers.json belong to whatever tree it was written for, not to this one.
  for (MarkerLink& m : listed) m.branch.reset();
  const fs::path camera_path = context.Result("register/pull_camera.json");
  const std::optional<Eigen::Isometry3d> camera = registration::ReadPullCameraJson(camera_path);
  if (!camera) throw InputError(camera_path.string(), "placed", "expected a placed pull camera");
  const Tree tree = ReadTreeJson(context.Result("reconstruct/static.json"));
  const identification::TreeMarkers placed =
      identification::MarkersOnTree(tree, tracks, *camera, listed);

  const std::vector<int> held_out = ChooseHeldOut(placed.markers, context.options.held_out_markers);
  std::vector<MarkerLink> given = placed.markers;
  std::erase_if(given, [&](const MarkerLink& m) {
    return std::find(held_out.begin(), held_out.end(), m.id) != held_out.end();
  });
  const identification::IdentificationResult result = identification::IdentifyMaterials(
      WithoutMarkers(tracks, held_out), given, {}, "track/trajectories.csv");
  const identification::MaterialsFile materials =
      identification::MaterialsFromIdentification(result, "track/trajectories.csv");
  identification::WriteMaterialsJson(materials, context.out_dir / "materials.json");
  WritePlacements(placed, held_out, context.out_dir / "placements.json");
  return fmt::format(
      "{} links, {} measured, {} branches; release at {:.2f} s; markers {} held "
      "out",
      materials.links.size(), materials.ranges.measured, materials.branches.size(),
      materials.release_time_s, fmt::join(held_out, ", "));
}

}  // namespace simtree::pipeline::detail
