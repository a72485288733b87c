#pragma once
// The depth camera's measurement: from what the optics see at every pixel (the renderer's exact
// depth, incidence and projected width) to the 16-bit millimetre image the sensor reports, with
// the errors of SensorModel (sensor_model.h, docs/sensor.md). Kept apart from ray casting so the
// noise model can be tested on hand-made truth images.

#include <cstdint>
#include <string>
#include <vector>

#include "simtree/io/image_io.h"
#include "simtree/synth/detail/sensor_model.h"

namespace simtree::synth {

// What the optics see at one pixel centre.
struct PixelTruth {
  float depth_m = 0.0f;        // camera z of the surface; 0 = nothing (sky)
  float cos_incidence = 1.0f;  // |cos| of the angle between the ray and the surface normal
  float width_px = 0.0f;       // projected width 2 r f / z of a thin curve there; 0 for surfaces
};

using DepthTruthImage = Image<PixelTruth, 1>;  // row-major, at(x, y)

// What happened to a pixel's measurement (the first effect that decided it).
enum class DepthEffect : uint8_t {
  kMeasured = 0,    // a surface, measured with noise
  kNoReturn,        // nothing there (sky)
  kOutOfRange,      // a surface outside the range (true or measured distance)
  kThinDropout,     // a curve too thin to measure
  kGrazingDropout,  // a surface seen at grazing incidence
  kEdgeDropout,     // dropped on a depth discontinuity
  kFlyingPixel,     // on a discontinuity, measured between the near and the far surface
  kOutlier,         // a random depth (sunlight)
};
const char* ToString(DepthEffect effect);

struct MeasureOptions {
  uint64_t seed = 0;
  int64_t frame = 0;
};

struct MeasureResult {
  DepthImage depth;                  // millimetres (intrinsics' depth_scale_m), 0 = none
  std::vector<DepthEffect> effects;  // per pixel, row-major
  // Pixels per effect, indexed by DepthEffect.
  std::vector<int64_t> counts;
  int64_t count(DepthEffect effect) const { return counts[static_cast<size_t>(effect)]; }
};

// Applies the sensor's errors. Throws InputError when `truth` is not the sensor's size or holds a
// depth that is negative or not finite.
MeasureResult MeasureDepth(const SensorModel& sensor, const DepthTruthImage& truth,
                           const MeasureOptions& options = {});

}  // namespace simtree::synth
