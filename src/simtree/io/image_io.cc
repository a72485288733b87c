#include "simtree/io/image_io.h"

#include <string>

#include <fmt/format.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "simtree/core/atomic_file.h"
#include "simtree/core/error.h"

namespace fs = std::filesystem;

namespace simtree {
namespace {

std::string DepthName(int cv_depth) {
  switch (cv_depth) {
    case CV_8U:
      return "8-bit";
    case CV_16U:
      return "16-bit";
    case CV_32F:
      return "32-bit float";
    default:
      return fmt::format("OpenCV depth {}", cv_depth);
  }
}

// Decodes the file as it is stored (bit depth and channels untouched).
cv::Mat Decode(const fs::path& path) {
  const std::string bytes = ReadFile(path);  // IoError naming the file when it is missing
  if (bytes.empty()) throw InputError(path.string(), "", "expected an image, the file is empty");
  // Only PNG, JPEG and BMP (the authors' leaf textures) reach OpenCV: imdecode tries every decoder
  // it has on anything else, and some abort on bad input (GDCM's DICOM reader asserted on a fuzzed
  // file).
  const bool known = bytes.starts_with("\x89PNG\r\n\x1a\n") || bytes.starts_with("\xff\xd8\xff") ||
                     bytes.starts_with("BM");
  if (!known) {
    throw InputError(path.string(), "",
                     "expected a PNG, JPEG or BMP image, the file is none of these");
  }
  const cv::Mat buffer(1, static_cast<int>(bytes.size()), CV_8U, const_cast<char*>(bytes.data()));
  cv::Mat image = cv::imdecode(buffer, cv::IMREAD_UNCHANGED);
  if (image.empty()) {
    throw InputError(path.string(), "", "expected a PNG or JPEG image, cannot decode it");
  }
  return image;
}

std::string Encode(const cv::Mat& image, const PngOptions& options) {
  std::vector<uchar> out;
  const std::vector<int> params = {cv::IMWRITE_PNG_COMPRESSION,
                                   std::clamp(options.compression, 0, 9)};
  if (!cv::imencode(".png", image, out, params)) throw Error("PNG encoding failed");
  return std::string(out.begin(), out.end());
}

}  // namespace

RgbImage ReadColorImage(const fs::path& path) {
  const cv::Mat image = Decode(path);
  if (image.depth() != CV_8U) {
    throw InputError(
        path.string(), "",
        fmt::format("expected an 8-bit colour image, got {}", DepthName(image.depth())));
  }
  cv::Mat rgb;
  switch (image.channels()) {
    case 1:
      cv::cvtColor(image, rgb, cv::COLOR_GRAY2RGB);
      break;
    case 3:
      cv::cvtColor(image, rgb, cv::COLOR_BGR2RGB);
      break;
    case 4:
      cv::cvtColor(image, rgb, cv::COLOR_BGRA2RGB);
      break;
    default:
      throw InputError(path.string(), "",
                       fmt::format("expected 1, 3 or 4 channels, got {}", image.channels()));
  }
  RgbImage out(rgb.cols, rgb.rows);
  for (int y = 0; y < rgb.rows; ++y) {
    std::memcpy(&out.at(0, y), rgb.ptr<uint8_t>(y), static_cast<size_t>(rgb.cols) * 3);
  }
  return out;
}

DepthImage ReadDepthImage(const fs::path& path) {
  const cv::Mat image = Decode(path);
  if (image.depth() != CV_16U || image.channels() != 1) {
    throw InputError(path.string(), "",
                     fmt::format("expected a 16-bit single-channel depth image (millimetres), got "
                                 "{} with {} channel(s)",
                                 DepthName(image.depth()), image.channels()));
  }
  DepthImage out(image.cols, image.rows);
  for (int y = 0; y < image.rows; ++y) {
    std::memcpy(&out.at(0, y), image.ptr<uint16_t>(y), static_cast<size_t>(image.cols) * 2);
  }
  return out;
}

std::string EncodePng(const RgbImage& image, const PngOptions& options) {
  if (image.empty()) throw Error("EncodePng: empty colour image");
  const cv::Mat rgb(image.height, image.width, CV_8UC3, const_cast<uint8_t*>(image.pixels.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  return Encode(bgr, options);
}

std::string EncodePng(const DepthImage& image, const PngOptions& options) {
  if (image.empty()) throw Error("EncodePng: empty depth image");
  const cv::Mat depth(image.height, image.width, CV_16UC1,
                      const_cast<uint16_t*>(image.pixels.data()));
  return Encode(depth, options);
}

void WritePng(const RgbImage& image, const fs::path& path, const PngOptions& options) {
  WriteFileAtomically(path, EncodePng(image, options));
}

void WritePng(const DepthImage& image, const fs::path& path, const PngOptions& options) {
  WriteFileAtomically(path, EncodePng(image, options));
}

}  // namespace simtree
