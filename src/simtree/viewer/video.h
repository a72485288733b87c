#pragma once
// Video from numbered PNG frames through the ffmpeg command line (H.264 in MP4, yuv420p so every
// player opens it). The file appears whole or not at all.

#include <filesystem>
#include <string>

namespace simtree::viewer {

struct VideoOptions {
  double fps = 30.0;                 // frames per second the video plays at (> 0)
  int crf = 18;                      // x264 quality: 0 lossless .. 51 worst; 18 looks lossless
  std::string pattern = "%06d.png";  // frame file names in the folder (printf style, not empty)

  // Throws InputError ("video options", the field) for a value out of range.
  void Validate() const;
};

// Encodes `frames_dir`/pattern into `output`. Throws InputError for options out of range, and
// simtree::Error when ffmpeg is missing or fails (with the last lines it printed).
void EncodeVideo(const std::filesystem::path& frames_dir, const std::filesystem::path& output,
                 const VideoOptions& options = {});

}  // namespace simtree::viewer
