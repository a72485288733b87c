// Blurs every colour PNG of a folder into another, as an out-of-focus lens (a Gaussian of
// --sigma px) or a camera moving sideways during the exposure (a horizontal line of --motion px)
// blurs it: the damaged pull streams of bench/capture_check_blur.sh.
//
//   blur_frames capture/pull/color blurred/pull/color --sigma 1.5
//   blur_frames capture/pull/color blurred/pull/color --motion 6
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "simtree/io/image_io.h"

namespace fs = std::filesystem;
using namespace simtree;

namespace {

void Blur(RgbImage& image, double sigma_px, int motion_px) {
  cv::Mat rgb(image.height, image.width, CV_8UC3, image.pixels.data());
  if (sigma_px > 0) cv::GaussianBlur(rgb, rgb, cv::Size(0, 0), sigma_px);
  if (motion_px > 1) {
    const cv::Mat line = cv::Mat::ones(1, motion_px, CV_32F) / motion_px;
    cv::filter2D(rgb, rgb, -1, line, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Blurs every colour PNG of a folder (bench/capture_check_blur.sh)");
  fs::path in, out;
  double sigma_px = 0;
  int motion_px = 0;
  app.add_option("in", in, "Folder of colour PNGs")->required()->check(CLI::ExistingDirectory);
  app.add_option("out", out, "Folder to write them to (created)")->required();
  app.add_option("--sigma", sigma_px, "Gaussian blur, px")->check(CLI::NonNegativeNumber);
  app.add_option("--motion", motion_px, "Horizontal motion blur, px")
      ->check(CLI::NonNegativeNumber);
  CLI11_PARSE(app, argc, argv);
  fs::create_directories(out);
  int count = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(in)) {
    if (entry.path().extension() != ".png") continue;
    RgbImage image = ReadColorImage(entry.path());
    Blur(image, sigma_px, motion_px);
    WritePng(image, out / entry.path().filename());
    ++count;
  }
  fmt::print("{} frames blurred (sigma {} px, motion {} px)\n", count, sigma_px, motion_px);
  return 0;
}
