#pragma once
// A picture to check depth-to-colour registration by eye: left, the colour image blended with
// false-colour depth (pixels without depth dimmed); right, the colour image with depth edges
// (jumps over 5 cm between neighbours) drawn in green, which must follow the objects' outlines.
// Half the colour image's size per panel.

#include "simtree/io/image_io.h"

namespace simtree::azure_detail {

RgbImage RegistrationOverlay(const RgbImage& color, const DepthImage& depth_in_color);

}  // namespace simtree::azure_detail
