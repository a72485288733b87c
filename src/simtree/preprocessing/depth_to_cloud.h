#pragma once
// An RGB-D image to a point cloud in the camera frame (OpenCV axes: x right, y down, z forward),
// one point per pixel with a depth inside the range, coloured from the registered colour image.

#include <open3d/geometry/PointCloud.h>

#include "simtree/io/capture.h"

namespace simtree::preprocessing {

struct DepthToCloudOptions {
  // Depths outside [min_depth_m, max_depth_m] are dropped (the Azure Kinect NFOV unbinned mode
  // measures 0.5-3.86 m; a little margin either side).
  double min_depth_m = 0.25;  // m, >= 0
  double max_depth_m = 6.0;   // m, >= min_depth_m
  int stride = 1;             // take every stride-th pixel in x and y, >= 1 (1: all)
  // Flying pixels: a time-of-flight pixel on a depth edge mixes the near and the far surface and
  // lands in between, on neither. A pixel none of whose 8 neighbours is within
  // max(flying_min_jump_m, flying_jump_share * depth) of its depth is dropped as one.
  double flying_min_jump_m = 0.03;   // m, >= 0 (0: keep every pixel)
  double flying_jump_share = 0.015;  // of the pixel's depth, [0, 1]
  bool with_colors = true;           // colour the points from the colour image

  // Throws InputError naming the field of a nonsense value.
  void Validate() const;
};

// Throws InputError for nonsense options, and (naming `source`) when the depth or colour image does
// not match the intrinsics. An image with no valid depth gives an empty cloud.
open3d::geometry::PointCloud DepthToCloud(const RgbdImage& image,
                                          const DepthToCloudOptions& options = {},
                                          const std::string& source = "<memory>");

}  // namespace simtree::preprocessing
