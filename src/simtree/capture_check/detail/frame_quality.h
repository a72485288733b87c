#pragma once
// What one RGB-D frame says about the tree in it: where the tree is (its preprocessed points
// projected into the image), how much of it has depth, how far it is, how sharp and how well
// blurred and how well exposed its colour is.

#include <cstdint>
#include <vector>

#include <open3d/geometry/PointCloud.h>

#include "simtree/io/capture.h"

namespace simtree::capture_check::detail {

struct FrameQuality {
  int tree_pixels = 0;      // pixels of the tree's footprint with depth
  int hole_pixels = 0;      // pixels without depth inside it (between depth pixels of the tree)
  double depth_share = 0;   // tree_pixels / (tree_pixels + hole_pixels)
  double distance_m = 0;    // median depth of the tree's points
  double blur = 0;          // BlurEffect over the footprint, 0 (sharp) to 1
  double bright_share = 0;  // footprint pixels with a channel at 250 or more (clipped)
  double dark_share = 0;    // footprint pixels whose brightest channel is below 28
};

// The tree's footprint: pixels of `tree_camera` (camera-frame points, e.g. a preprocessed,
// downsampled cloud) projected, grown by about half a point spacing, kept where the depth agrees
// with the tree's (within 0.15 m of a projected point's), and the holes: pixels without depth
// with footprint pixels at most 3 px away on both sides (in a row or a column).
FrameQuality MeasureFrame(const RgbdImage& image, const open3d::geometry::PointCloud& tree_camera,
                          double point_spacing_m);

// How blurred the grey image is over `mask`, 0 (sharp) to 1, whatever the scene's contrast: the
// share of its neighbour differences that a further blur (a 3 px box, along the row and along the
// column) leaves in place, the larger of the two directions (the "blur effect" of Crete-Roffet et
// al., 2007, at the scale of thin tapes). A sharp edge loses most of its step to the box; an edge
// already blurred over the box's width keeps it. 0 when the mask holds no contrast.
double BlurEffect(const RgbImage& color, const std::vector<uint8_t>& mask);

}  // namespace simtree::capture_check::detail
