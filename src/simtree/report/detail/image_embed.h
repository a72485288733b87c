#pragma once
// Images inlined into the page as data: URIs. A picture is scaled down to a width and encoded as
// PNG or JPEG, whichever is smaller unless PNG costs at most a third more (drawings and plots stay
// sharp, photographs and renders become JPEG).

#include <cstdint>
#include <filesystem>
#include <string>

#include "simtree/io/image_io.h"

namespace simtree::report {

struct ImageEmbedOptions {
  int max_width = 960;               // wider images are scaled down (aspect kept)
  int jpeg_quality = 85;             // 0-100
  double png_allowance = 4.0 / 3.0;  // PNG is kept while it is at most this times the JPEG
};

struct EmbeddedImage {
  std::string data_uri;                     // "data:image/png;base64,..."
  std::string mime;                         // "image/png" or "image/jpeg"
  int width = 0, height = 0;                // as embedded
  int source_width = 0, source_height = 0;  // as read
  int64_t bytes() const { return static_cast<int64_t>(data_uri.size()); }
};

// Reads an 8- or 16-bit PNG or JPEG (16-bit is scaled to 8). Throws InputError naming the file
// when it cannot be read as an image.
EmbeddedImage EmbedImageFile(const std::filesystem::path& path,
                             const ImageEmbedOptions& options = {});

// The same for an image in memory (8-bit RGB).
EmbeddedImage EmbedRgbImage(const RgbImage& image, const ImageEmbedOptions& options = {});

}  // namespace simtree::report
