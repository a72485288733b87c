#pragma once
// Marker trajectories of a pull test (docs/formats.md). The marker list
// markers.json (how markers link into the simplified tree of paper Fig. 8) is read by
// io/capture.h (ReadMarkersJson).
//
//  - trajectories.csv (`simtree.trajectories` v1): what `track` writes, what `synth` writes as
//    ground truth and what `identify` reads. A comment line
//    `# simtree.trajectories v1 frame=camera units=m`, the header
//    `frame,time_s,marker,x,y,z,valid`, then one row per (frame, marker): the marker centre in the
//    pull camera's frame (OpenCV axes, metres), valid 1 or 0 (occluded or lost; x, y, z then empty
//    or nan).

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace simtree {

inline constexpr const char* kTrajectoriesFirstLine =
    "# simtree.trajectories v1 frame=camera units=m";
inline constexpr const char* kTrajectoriesHeader = "frame,time_s,marker,x,y,z,valid";

// The track of one marker: a position per frame of the owning Trajectories, NaN when not valid.
struct MarkerTrack {
  int marker = 0;
  std::vector<Eigen::Vector3d> positions;  // camera frame, metres
  std::vector<bool> valid;

  int valid_count() const;
};

// All markers over all frames. Every track has one entry per frame.
struct Trajectories {
  std::vector<int> frames;      // frame numbers, increasing
  std::vector<double> times_s;  // increasing
  std::vector<MarkerTrack> tracks;

  int frame_count() const { return static_cast<int>(frames.size()); }
  int marker_count() const { return static_cast<int>(tracks.size()); }
  // Index into `tracks` of a marker id, or -1.
  int IndexOf(int marker) const;
  const MarkerTrack* Find(int marker) const;
  // Adds a frame with one position per track (NaN or invalid entries for lost markers).
  void AddFrame(int frame, double time_s, const std::vector<Eigen::Vector3d>& positions,
                const std::vector<bool>& valid);
};

// Parses trajectories.csv text; `source` names it in errors (InputError with the line). Checks
// the first line and header, frames and times increasing, every marker in every frame exactly once
// (markers in the same order in every frame), valid in {0, 1}, finite positions when valid.
Trajectories ParseTrajectoriesCsv(const std::string& text, const std::string& source);
Trajectories ReadTrajectoriesCsv(const std::filesystem::path& path);
std::string TrajectoriesToCsv(const Trajectories& trajectories);
// Checks the same rules as the reader, then writes atomically. Positions are written in metres
// with 6 decimals (1 µm), times with 6 decimals.
void WriteTrajectoriesCsv(const Trajectories& trajectories, const std::filesystem::path& path);

}  // namespace simtree
