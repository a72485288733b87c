#pragma once
// Pictures of depth and label images for people: a false-colour depth (near warm, far cool, no
// measurement black) and a label map (tape red, branches by id, ground, background, sky).

#include "simtree/io/image_io.h"
#include "simtree/synth/rgbd_labels.h"

namespace simtree {

// Depth in [near_m, far_m] mapped through a perceptual rainbow; 0 (no measurement) is black.
// `depth_scale_m` is metres per depth unit.
RgbImage ColorizeDepth(const DepthImage& depth, double near_m, double far_m,
                       double depth_scale_m = 0.001);

RgbImage ColorizeLabels(const LabelImage& labels);

}  // namespace simtree
