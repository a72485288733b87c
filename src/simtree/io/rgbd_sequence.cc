#include "simtree/io/rgbd_sequence.h"

#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "simtree/core/error.h"

namespace simtree {

namespace fs = std::filesystem;

DepthImage DepthToMillimetres(const DepthImage& raw, double units_per_m, int* out_of_range) {
  if (units_per_m == 1000.0) return raw;  // already millimetres: no rounding at all
  const double mm_per_unit = 1000.0 / units_per_m;
  DepthImage mm(raw.width, raw.height);
  int beyond = 0;
  for (size_t i = 0; i < raw.pixels.size(); ++i) {
    if (raw.pixels[i] == 0) continue;
    const double value = std::round(raw.pixels[i] * mm_per_unit);
    if (value > std::numeric_limits<uint16_t>::max()) {
      ++beyond;
      continue;
    }
    mm.pixels[i] = static_cast<uint16_t>(value);
  }
  if (out_of_range) *out_of_range = beyond;
  return mm;
}

RgbdFileSequence::RgbdFileSequence(std::string source, std::string sensor,
                                   const CameraIntrinsics& intrinsics, double depth_units_per_m,
                                   std::vector<RgbdFileFrame> frames)
    : source_(std::move(source)),
      sensor_(std::move(sensor)),
      intrinsics_(intrinsics),
      depth_units_per_m_(depth_units_per_m),
      frames_(std::move(frames)) {
  intrinsics_.depth_scale_m = 0.001;
  ValidateIntrinsics(intrinsics_, source_);
  if (!(depth_units_per_m_ > 0) || !std::isfinite(depth_units_per_m_)) {
    throw InputError(source_, "depth scale",
                     fmt::format("expected a positive number of depth units per metre, got {}",
                                 depth_units_per_m_));
  }
}

RgbImage RgbdFileSequence::LoadColor(size_t index) const {
  const RgbdFileFrame& f = frames_.at(index);
  RgbImage color = ReadColorImage(f.color);
  if (color.width != intrinsics_.width || color.height != intrinsics_.height) {
    throw InputError(f.color.string(), "",
                     fmt::format("expected a {}x{} colour image (the intrinsics' size), got {}x{}",
                                 intrinsics_.width, intrinsics_.height, color.width, color.height));
  }
  return color;
}

RgbdImage RgbdFileSequence::Load(size_t index) const {
  const RgbdFileFrame& f = frames_.at(index);
  RgbdImage image;
  image.intrinsics = intrinsics_;
  image.color = LoadColor(index);
  const DepthImage raw = ReadDepthImage(f.depth);
  if (raw.width != intrinsics_.width || raw.height != intrinsics_.height) {
    throw InputError(f.depth.string(), "",
                     fmt::format("expected a {}x{} depth image (registered to the colour "
                                 "image {}), got {}x{}",
                                 intrinsics_.width, intrinsics_.height, f.color.filename().string(),
                                 raw.width, raw.height));
  }
  image.depth = DepthToMillimetres(raw, depth_units_per_m_, nullptr);
  return image;
}

}  // namespace simtree
