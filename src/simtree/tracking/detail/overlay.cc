#include "simtree/tracking/detail/overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "simtree/core/error.h"

namespace fs = std::filesystem;

namespace simtree::tracking::detail {
namespace {

cv::Scalar StateColor(MarkerState state) {  // RGB order: the image is RGB
  switch (state) {
    case MarkerState::kTracked:
      return {40, 230, 40};
    case MarkerState::kPredicted:
      return {250, 220, 30};
    case MarkerState::kLost:
      return {230, 40, 40};
  }
  return {255, 255, 255};
}

// Draws at twice the image size so boxes of a few pixels stay readable.
constexpr int kZoom = 2;

cv::Point Scaled(double x, double y) {
  return {static_cast<int>(std::lround(x * kZoom)), static_cast<int>(std::lround(y * kZoom))};
}

std::string Quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

fs::path FindOnPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return {};
  std::string dirs = path;
  size_t start = 0;
  while (start <= dirs.size()) {
    const size_t end = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(start, end - start)) / program;
    std::error_code ec;
    if (end > start && fs::is_regular_file(candidate, ec)) return candidate;
    start = end + 1;
  }
  return {};
}

}  // namespace

RgbImage DrawOverlay(const RgbImage& color, const TrackResult& result, size_t index,
                     int trail_frames) {
  cv::Mat src(color.height, color.width, CV_8UC3, const_cast<uint8_t*>(color.pixels.data()));
  cv::Mat canvas;
  cv::resize(src, canvas, cv::Size(), kZoom, kZoom, cv::INTER_NEAREST);
  const FrameBoxes& frame = result.boxes[index];
  for (size_t m = 0; m < frame.markers.size(); ++m) {
    // Trail: the centres of the last frames the marker was tracked in.
    const size_t first = index >= static_cast<size_t>(trail_frames) ? index - trail_frames : 0;
    for (size_t k = first; k + 1 <= index; ++k) {
      const MarkerBox& a = result.boxes[k].markers[m];
      const MarkerBox& b = result.boxes[k + 1].markers[m];
      if (a.state != MarkerState::kTracked || b.state != MarkerState::kTracked) continue;
      cv::line(canvas, Scaled(a.center[0], a.center[1]), Scaled(b.center[0], b.center[1]),
               cv::Scalar(80, 200, 255), 1, cv::LINE_AA);
    }
    const MarkerBox& box = frame.markers[m];
    if (box.state == MarkerState::kLost) continue;
    const cv::Scalar c = StateColor(box.state);
    cv::rectangle(canvas, Scaled(box.box[0], box.box[1]),
                  Scaled(box.box[0] + box.box[2], box.box[1] + box.box[3]), c, 1);
    cv::putText(canvas, std::to_string(box.marker),
                Scaled(box.box[0] + box.box[2] + 1.0, box.box[1]), cv::FONT_HERSHEY_SIMPLEX, 0.4, c,
                1, cv::LINE_AA);
  }
  cv::putText(canvas, fmt::format("frame {}", frame.frame), cv::Point(8, 20),
              cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  RgbImage out(canvas.cols, canvas.rows);
  std::copy(canvas.data, canvas.data + out.pixels.size(), out.pixels.begin());
  return out;
}

void EncodeVideo(const fs::path& pattern, double fps, const fs::path& video) {
  const fs::path ffmpeg = FindOnPath("ffmpeg");
  if (ffmpeg.empty()) {
    throw IoError(
        fmt::format("{}: the overlay video needs the ffmpeg program (H.264), and it is "
                    "not on PATH; install ffmpeg or drop --video (the overlay PNG "
                    "frames are written)",
                    video.string()));
  }
  const std::string command = fmt::format(
      "{} -y -loglevel error -framerate {:.6f} -i {} -c:v libx264 -pix_fmt yuv420p "
      "-movflags +faststart -f mp4 {}",
      Quote(ffmpeg.string()), fps, Quote(pattern.string()), Quote(video.string()));
  const int status = std::system(command.c_str());
  if (status != 0) {
    throw IoError(fmt::format("{}: ffmpeg failed (exit status {}) running: {}", video.string(),
                              status, command));
  }
}

}  // namespace simtree::tracking::detail
