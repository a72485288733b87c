#pragma once
// Decoding one Azure Kinect frame: DEPTH and IR (`b16g`, big-endian 16-bit) to a uint16 image,
// COLOR (MJPEG, or raw NV12, YUY2, BGRA) to 8-bit RGB. Errors name the file, track and frame.

#include <cstdint>
#include <memory>
#include <string>

#include "simtree/io/detail/mkv_demuxer.h"
#include "simtree/io/image_io.h"

namespace simtree::azure_detail {

// Throws InputError unless `size` is width * height * 2 bytes.
DepthImage DecodeB16g(const uint8_t* data, int size, const AzureTrack& track,
                      const std::string& source, int frame);

class ColorDecoder {
 public:
  // Throws InputError naming the file when the track's format is not one the recorder writes.
  ColorDecoder(const MkvStream& stream, std::string source);
  ~ColorDecoder();
  ColorDecoder(const ColorDecoder&) = delete;
  ColorDecoder& operator=(const ColorDecoder&) = delete;

  RgbImage Decode(const uint8_t* data, int size, int frame);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace simtree::azure_detail
