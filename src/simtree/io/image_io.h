#pragma once
// Images as simtree passes them around (colour 8-bit RGB, depth 16-bit millimetres) and their PNG
// files. Plain row-major buffers, so callers need no imaging library; OpenCV stays inside the .cc.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace simtree {

// A row-major image with `kChannels` interleaved channels of type T.
template <typename T, int kChannels>
struct Image {
  static constexpr int channels = kChannels;
  int width = 0;
  int height = 0;
  std::vector<T> pixels;  // width * height * kChannels values, row after row

  Image() = default;
  Image(int w, int h, T fill = T{})
      : width(w), height(h), pixels(static_cast<size_t>(w) * h * kChannels, fill) {}

  bool empty() const { return width == 0 || height == 0; }
  size_t pixel_count() const { return static_cast<size_t>(width) * height; }
  T& at(int x, int y, int c = 0) {
    return pixels[(static_cast<size_t>(y) * width + x) * kChannels + c];
  }
  const T& at(int x, int y, int c = 0) const {
    return pixels[(static_cast<size_t>(y) * width + x) * kChannels + c];
  }
  bool operator==(const Image& other) const = default;
};

using RgbImage = Image<uint8_t, 3>;     // 8-bit R, G, B
using DepthImage = Image<uint16_t, 1>;  // millimetres along the camera z axis, 0 = no measurement

// zlib level of written PNGs: 0 (none) .. 9 (smallest). Level 1 is several times faster than the
// default for noisy images and only ~10% larger, which is what a 450-frame stream wants.
struct PngOptions {
  int compression = 1;
};

// Reads an 8-bit colour image (PNG, JPEG or BMP; grey and RGBA are converted to RGB). Throws
// InputError naming the file when it is missing, unreadable or not 8-bit.
RgbImage ReadColorImage(const std::filesystem::path& path);
// Reads a 16-bit single-channel PNG of millimetres. An 8-bit or colour image is refused (it cannot
// hold millimetres up to the sensor's range).
DepthImage ReadDepthImage(const std::filesystem::path& path);

// PNG bytes (deterministic: same pixels, same options, same bytes).
std::string EncodePng(const RgbImage& image, const PngOptions& options = {});
std::string EncodePng(const DepthImage& image, const PngOptions& options = {});

// Writes atomically (no partial file on failure).
void WritePng(const RgbImage& image, const std::filesystem::path& path,
              const PngOptions& options = {});
void WritePng(const DepthImage& image, const std::filesystem::path& path,
              const PngOptions& options = {});

}  // namespace simtree
