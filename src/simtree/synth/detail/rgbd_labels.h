#pragma once
// Per-pixel ground truth of a rendered RGB-D frame: what the ray through the pixel's centre hit
// (kind, branch, marker) and its exact depth, before any sensor error.

#include <cstdint>

#include "simtree/io/image_io.h"
#include "simtree/synth/detail/sensor_scene.h"

namespace simtree::synth {

struct PixelLabel {
  SurfaceKind kind = SurfaceKind::kNone;
  int32_t branch = -1;      // branch id on a branch
  int32_t marker = -1;      // marker id on a tape band
  float arc_length = 0.0f;  // rest arc length on the branch (metres)
  float depth_m = 0.0f;     // exact camera z of the surface; 0 where nothing is hit
};

using LabelImage = Image<PixelLabel, 1>;  // row-major, at(x, y)

}  // namespace simtree::synth
