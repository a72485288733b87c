// How many visible tape markers a bare colour threshold finds in a capture's pull stream: the
// figure that shows what a real camera's colour (docs/synth.md, "Colour as a camera delivers
// it") does to thin red tape. Per capture: the visible marker samples of gt/markers_2d.json, and
// the share of them with at least `--min-pixels` threshold pixels inside the box (grown by 1 px).
// The threshold is the textbook one for red: OpenCV HSV hue <= 10 or >= 170 (of 180),
// saturation >= 100, value >= 50.
//
//   build/bin/synth_color_threshold clean/ camera/ [--stride 5]   (a developer tool, not a test)
//   build/bin/synth_color_threshold clean/ --apply jpeg    (one part of the camera on clean frames)
//   build/bin/synth_color_threshold clean/ --apply all --crops crops.png   (frame 0's markers)

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "simtree/core/error.h"
#include "simtree/io/capture.h"
#include "simtree/io/ground_truth.h"
#include "simtree/io/image_io.h"
#include "simtree/synth/detail/camera_color.h"

namespace fs = std::filesystem;

namespace {

struct Count {
  long visible = 0, found = 0;
};

cv::Mat RedMask(const simtree::RgbImage& image) {
  cv::Mat rgb(image.height, image.width, CV_8UC3, const_cast<uint8_t*>(image.pixels.data()));
  cv::Mat hsv;
  cv::cvtColor(rgb, hsv, cv::COLOR_RGB2HSV);
  cv::Mat low, high;
  cv::inRange(hsv, cv::Scalar(0, 100, 50), cv::Scalar(10, 255, 255), low);
  cv::inRange(hsv, cv::Scalar(170, 100, 50), cv::Scalar(180, 255, 255), high);
  return low | high;
}

// The camera's options with only `part` of it on ("all": every part, "none": nothing).
simtree::synth::CameraColorOptions CameraPart(const std::string& part,
                                              const simtree::synth::CameraColorOptions& all) {
  simtree::synth::CameraColorOptions o;
  o.white_balance_error = o.exposure_drift_stops = o.read_noise_std = o.shot_noise_gain = 0.0;
  o.defocus_sigma_px = 0.0;
  o.jpeg_quality = 0;
  if (part == "all") return all;
  if (part == "wb") o.white_balance_error = all.white_balance_error;
  if (part == "exposure") o.exposure_drift_stops = all.exposure_drift_stops;
  if (part == "noise") {
    o.read_noise_std = all.read_noise_std;
    o.shot_noise_gain = all.shot_noise_gain;
  }
  if (part == "defocus") o.defocus_sigma_px = all.defocus_sigma_px;
  if (part == "jpeg") o.jpeg_quality = all.jpeg_quality;
  return o;
}

// 24 x 24 px around each visible marker of frame 0, shown 8x: a row of the frame as stored
// above the same after `camera`.
void WriteCrops(const simtree::RgbImage& stored, const simtree::RgbImage& camera,
                const simtree::MarkerFrame2d& frame, const fs::path& path) {
  constexpr int kHalf = 12, kZoom = 8, kTile = 2 * kHalf * kZoom;
  std::vector<const simtree::MarkerBox2d*> shown;
  for (const simtree::MarkerBox2d& m : frame.markers) {
    if (m.visible) shown.push_back(&m);
  }
  simtree::RgbImage out(kTile * static_cast<int>(shown.size()), 2 * kTile);
  for (size_t i = 0; i < shown.size(); ++i) {
    const int cx = static_cast<int>(shown[i]->box[0] + 0.5 * shown[i]->box[2]);
    const int cy = static_cast<int>(shown[i]->box[1] + 0.5 * shown[i]->box[3]);
    for (int y = 0; y < kTile; ++y) {
      for (int x = 0; x < kTile; ++x) {
        const int sx = std::clamp(cx - kHalf + x / kZoom, 0, stored.width - 1);
        const int sy = std::clamp(cy - kHalf + y / kZoom, 0, stored.height - 1);
        for (int c = 0; c < 3; ++c) {
          out.at(static_cast<int>(i) * kTile + x, y, c) = stored.at(sx, sy, c);
          out.at(static_cast<int>(i) * kTile + x, kTile + y, c) = camera.at(sx, sy, c);
        }
      }
    }
  }
  simtree::WritePng(out, path);
}

Count CountCapture(const fs::path& dir, int stride, int min_pixels, const std::string& apply,
                   const simtree::synth::CameraColorOptions& camera_options,
                   const fs::path& crops) {
  const simtree::Capture capture = simtree::OpenCapture(dir);
  if (!capture.pull) throw simtree::InputError(dir.string(), "pull", "expected a pull stream");
  const std::vector<simtree::MarkerFrame2d> boxes =
      simtree::ReadMarkers2d(dir / "gt" / "markers_2d.json");
  const simtree::synth::CameraColor camera(CameraPart(apply, camera_options), 1);
  Count count;
  for (size_t f = 0; f < boxes.size() && f < capture.pull->frames.size(); f += stride) {
    simtree::RgbdImage image = simtree::LoadPullFrame(*capture.pull, f);
    if (apply != "none") {
      const simtree::RgbImage stored = image.color;
      camera.Apply(capture.pull->frames[f].time_s, static_cast<int64_t>(f), image.color);
      if (f == 0 && !crops.empty()) WriteCrops(stored, image.color, boxes[0], crops);
    }
    const cv::Mat mask = RedMask(image.color);
    for (const simtree::MarkerBox2d& m : boxes[f].markers) {
      if (!m.visible) continue;
      ++count.visible;
      const int x0 = std::max(0, static_cast<int>(std::floor(m.box[0])) - 1);
      const int y0 = std::max(0, static_cast<int>(std::floor(m.box[1])) - 1);
      const int x1 = std::min(mask.cols, static_cast<int>(std::ceil(m.box[0] + m.box[2])) + 2);
      const int y1 = std::min(mask.rows, static_cast<int>(std::ceil(m.box[1] + m.box[3])) + 2);
      if (x1 <= x0 || y1 <= y0) continue;
      count.found += cv::countNonZero(mask(cv::Rect(x0, y0, x1 - x0, y1 - y0))) >= min_pixels;
    }
  }
  return count;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Share of visible tape markers a bare red colour threshold finds in captures");
  std::vector<std::string> captures;
  int stride = 1, min_pixels = 3;
  std::string apply = "none", crops;
  simtree::synth::CameraColorOptions camera_options;
  app.add_option("captures", captures, "Capture folders (simtree synth)")->required();
  app.add_option("--stride", stride, "Use every n-th frame")->check(CLI::Range(1, 1000));
  app.add_option("--min-pixels", min_pixels, "Threshold pixels in the box that count as found")
      ->check(CLI::Range(1, 100));
  app.add_option("--apply", apply,
                 "Apply the camera (or one part of it) to the stored frames first")
      ->check(CLI::IsMember({"none", "all", "wb", "exposure", "noise", "defocus", "jpeg"}));
  app.add_option("--crops", crops, "With --apply: write frame 0's markers before and after (PNG)");
  app.add_option("--jpeg-quality", camera_options.jpeg_quality, "With --apply: JPEG quality")
      ->capture_default_str();
  app.add_option("--defocus", camera_options.defocus_sigma_px, "With --apply: defocus sigma, px")
      ->capture_default_str();
  app.add_flag("--chroma-420{false},--chroma-422{true}", camera_options.chroma_422,
               "With --apply: chroma subsampling");
  CLI11_PARSE(app, argc, argv);
  try {
    Count total;
    for (const std::string& dir : captures) {
      const Count c = CountCapture(dir, stride, min_pixels, apply, camera_options, crops);
      std::printf("%s: %ld of %ld visible marker samples found (%.3f)\n", dir.c_str(), c.found,
                  c.visible, c.visible > 0 ? static_cast<double>(c.found) / c.visible : 0.0);
      total.visible += c.visible;
      total.found += c.found;
    }
    std::printf("all: %ld of %ld (%.3f)\n", total.found, total.visible,
                total.visible > 0 ? static_cast<double>(total.found) / total.visible : 0.0);
  } catch (const simtree::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
