#pragma once
// False-colour pictures of depth images, for people to look at (contact sheets, before/after
// pictures, reports). Not a measurement: depth files stay 16-bit millimetres.

#include "simtree/io/image_io.h"

namespace simtree {

struct DepthColormapOptions {
  // Depths mapped onto the colour ramp; nearer and farther values are clamped. The defaults are
  // the Azure Kinect's NFOV range, so pictures of different views compare.
  double near_m = 0.5;
  double far_m = 3.86;
  double depth_scale_m = 0.001;  // metres per depth unit
};

// Near is warm (red-yellow), far is cool (blue-violet), no measurement (0) is black.
RgbImage ColorizeDepth(const DepthImage& depth, const DepthColormapOptions& options = {});

}  // namespace simtree
