#pragma once
// Playback against measurement: tracked markers (trajectories.csv from `track`, or the world-frame
// markers.csv of `simtree simulate`) shown beside the simulated markers, with the distance between
// each pair at the same time.

#include <filesystem>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "simtree/core/tree.h"
#include "simtree/dynamics/tree_dynamics.h"
#include "simtree/io/trajectories.h"

namespace simtree::viewer {

// Reads marker tracks and brings them into the world frame. A camera-frame file (what `track`
// writes) needs `world_from_camera` (the pull camera's pose; InputError without it); a world-frame
// file (what `simulate` writes) is taken as it is.
Trajectories ReadTracksInWorld(const std::filesystem::path& path,
                               const std::optional<Eigen::Isometry3d>& world_from_camera);

// The position of track `index` at time t: linear between the two frames around t when both are
// valid; nullopt outside the record or next to an invalid frame.
std::optional<Eigen::Vector3d> TrackPositionAt(const Trajectories& tracks, int index, double t);

struct MarkerError {
  int marker = 0;
  std::string label;
  Eigen::Vector3d measured = Eigen::Vector3d::Zero();
  Eigen::Vector3d simulated = Eigen::Vector3d::Zero();
  double error_m = 0.0;
};

struct MarkerComparison {
  std::vector<MarkerError> markers;  // the markers measured at this time, in `markers` order
  double rms_error_m = 0.0;          // over them; 0 when none
  double max_error_m = 0.0;
};

// The simulated markers (each at its branch and arc length in `sim`) against the measured ones of
// the same id at the simulation's time.
MarkerComparison CompareMarkers(const Trajectories& measured, const std::vector<Marker>& markers,
                                const dynamics::TreeDynamics& sim);

}  // namespace simtree::viewer
