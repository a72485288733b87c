#pragma once
// What one RGB-D frame says about the tree in it: where the tree is (its preprocessed points
// projected into the image), how much of it has depth, how far it is, how sharp and how well
// exposed its colour is.

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
  double sharpness = 0;     // variance of the grey Laplacian over the footprint
  double bright_share = 0;  // footprint pixels with a channel at 250 or more (clipped)
  double dark_share = 0;    // footprint pixels whose brightest channel is below 28
};

// The tree's footprint: pixels of `tree_camera` (camera-frame points, e.g. a preprocessed,
// downsampled cloud) projected, grown by about half a point spacing, kept where the depth agrees
// with the tree's (within 0.15 m of a projected point's), and the holes: pixels without depth
// with footprint pixels at most 3 px away on both sides (in a row or a column).
FrameQuality MeasureFrame(const RgbdImage& image, const open3d::geometry::PointCloud& tree_camera,
                          double point_spacing_m);

// Variance of the Laplacian of the grey image over the pixels of `mask` (non-zero), 0 when
// empty: low when the colour is blurred (motion, focus).
double Sharpness(const RgbImage& color, const std::vector<uint8_t>& mask);

}  // namespace simtree::capture_check::detail
