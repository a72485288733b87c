#include "simtree/viewer/marker_playback.h"

#include <algorithm>
#include <cmath>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"
#include "simtree/dynamics/recorders.h"

namespace simtree::viewer {

Trajectories ReadTracksInWorld(const std::filesystem::path& path,
                               const std::optional<Eigen::Isometry3d>& world_from_camera) {
  std::string text = ReadFile(path);
  const std::string world_line = dynamics::kWorldTrajectoriesFirstLine;
  const bool world = text.rfind(world_line, 0) == 0;
  // The world-frame variant differs only in its first line: read it with the same checks.
  if (world) text.replace(0, world_line.size(), kTrajectoriesFirstLine);
  Trajectories tracks = ParseTrajectoriesCsv(text, path.string());
  if (world) return tracks;
  if (!world_from_camera) {
    throw InputError(path.string(), "line 1",
                     "the markers are in the pull camera's frame: give the camera's pose "
                     "(--camera-pose gt/pull_camera.json) to place them in the world");
  }
  for (MarkerTrack& track : tracks.tracks) {
    for (Eigen::Vector3d& p : track.positions) p = *world_from_camera * p;
  }
  return tracks;
}

std::optional<Eigen::Vector3d> TrackPositionAt(const Trajectories& tracks, int index, double t) {
  if (index < 0 || index >= tracks.marker_count() || tracks.frame_count() == 0) {
    return std::nullopt;
  }
  const std::vector<double>& times = tracks.times_s;
  const MarkerTrack& track = tracks.tracks[index];
  if (!std::isfinite(t) || t < times.front() || t > times.back()) return std::nullopt;
  const size_t hi = std::min<size_t>(
      std::lower_bound(times.begin(), times.end(), t) - times.begin(), times.size() - 1);
  const size_t lo = hi == 0 ? 0 : (times[hi] == t ? hi : hi - 1);
  if (!track.valid[lo] || !track.valid[hi]) return std::nullopt;
  if (lo == hi) return track.positions[lo];
  const double f = (t - times[lo]) / (times[hi] - times[lo]);
  return (1.0 - f) * track.positions[lo] + f * track.positions[hi];
}

MarkerComparison CompareMarkers(const Trajectories& measured, const std::vector<Marker>& markers,
                                const dynamics::TreeDynamics& sim) {
  MarkerComparison out;
  double sum_sq = 0.0;
  for (const Marker& m : markers) {
    const auto p = TrackPositionAt(measured, measured.IndexOf(m.id), sim.time());
    if (!p || m.branch < 0 || m.branch >= sim.branch_count()) continue;
    MarkerError e;
    e.marker = m.id;
    e.label = m.label;
    e.measured = *p;
    e.simulated = sim.PointPosition(m.branch, m.arc_length);
    e.error_m = (e.measured - e.simulated).norm();
    sum_sq += e.error_m * e.error_m;
    out.max_error_m = std::max(out.max_error_m, e.error_m);
    out.markers.push_back(e);
  }
  if (!out.markers.empty()) out.rms_error_m = std::sqrt(sum_sq / out.markers.size());
  return out;
}

}  // namespace simtree::viewer
