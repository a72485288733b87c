#pragma once
// The tracker's start: each marker's pixel in one frame of the pull stream, as a person clicks it
// (`simtree track --pick`), as `synth` writes it (pull/init.json), or as a converter of a real
// recording gives it. File format `simtree.track_init` v1 (docs/formats.md):
//
//   {"format": "simtree.track_init", "version": 1, "frame": 0,
//    "markers": [{"id": 0, "pixel": [312.4, 401.2]}, {"id": 1, "pixel": [298.0, 250.5]}]}
//
//   const TrackInit init = ReadTrackInitJson(capture / "pull" / "init.json");
//   for (const MarkerPixel& m : init.markers) Seed(m.id, m.pixel);

#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace simtree {

// One marker's position in the colour image: pixel centres at integer coordinates (OpenCV).
struct MarkerPixel {
  int id = 0;             // the marker's id in markers.json
  Eigen::Vector2d pixel;  // (column, row), px
};

struct TrackInit {
  int frame = 0;                     // the frame number (pull/frames.csv) the pixels belong to
  std::vector<MarkerPixel> markers;  // at least one; ids unique
};

// Reads init.json. Errors name the file and field: a missing file, a wrong format or version, an
// empty marker list, an id < 0 or given twice, a pixel that is not two finite numbers >= 0.
TrackInit ReadTrackInitJson(const std::filesystem::path& path);

// Writes init.json atomically (6 decimals, 1 micro-pixel).
void WriteTrackInitJson(const TrackInit& init, const std::filesystem::path& path);

}  // namespace simtree
