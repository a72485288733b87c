#include "simtree/report/detail/image_embed.h"

#include <string_view>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "simtree/core/error.h"
#include "simtree/report/detail/base64.h"

namespace simtree::report {
namespace {

std::string Encode(const cv::Mat& image, const char* ext, const std::vector<int>& params) {
  std::vector<uchar> bytes;
  cv::imencode(ext, image, bytes, params);
  return std::string(bytes.begin(), bytes.end());
}

// Scales `image` (BGR, 8-bit) to the options' width and encodes it.
EmbeddedImage EmbedMat(cv::Mat image, const ImageEmbedOptions& options) {
  EmbeddedImage out;
  out.source_width = image.cols;
  out.source_height = image.rows;
  if (options.max_width > 0 && image.cols > options.max_width) {
    const int height = std::max(
        1, static_cast<int>(
               std::lround(image.rows * static_cast<double>(options.max_width) / image.cols)));
    cv::resize(image, image, cv::Size(options.max_width, height), 0, 0, cv::INTER_AREA);
  }
  out.width = image.cols;
  out.height = image.rows;
  const std::string png = Encode(image, ".png", {cv::IMWRITE_PNG_COMPRESSION, 9});
  const std::string jpeg = Encode(image, ".jpg", {cv::IMWRITE_JPEG_QUALITY, options.jpeg_quality});
  const bool use_png = static_cast<double>(png.size()) <= options.png_allowance * jpeg.size();
  out.mime = use_png ? "image/png" : "image/jpeg";
  out.data_uri = "data:" + out.mime + ";base64," + Base64Encode(use_png ? png : jpeg);
  return out;
}

}  // namespace

EmbeddedImage EmbedImageFile(const std::filesystem::path& path, const ImageEmbedOptions& options) {
  cv::Mat image = cv::imread(path.string(), cv::IMREAD_ANYDEPTH | cv::IMREAD_COLOR);
  if (image.empty()) {
    throw InputError(path.string(), "", "expected a PNG or JPEG image that can be read");
  }
  if (image.depth() == CV_16U) image.convertTo(image, CV_8U, 1.0 / 257.0);
  return EmbedMat(image, options);
}

EmbeddedImage EmbedRgbImage(const RgbImage& image, const ImageEmbedOptions& options) {
  cv::Mat rgb(image.height, image.width, CV_8UC3, const_cast<uint8_t*>(image.pixels.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  return EmbedMat(bgr, options);
}

}  // namespace simtree::report
