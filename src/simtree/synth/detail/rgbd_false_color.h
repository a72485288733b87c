#pragma once
// Pictures of label images for people: a label map (tape red, branches by id, ground, background,
// sky). False-colour depth is io/depth_colormap.h.

#include "simtree/io/image_io.h"
#include "simtree/synth/detail/rgbd_labels.h"

namespace simtree::synth {

RgbImage ColorizeLabels(const LabelImage& labels);

}  // namespace simtree::synth
