#pragma once
// Depth registered into the colour camera, as the Azure Kinect SDK's depth-to-colour
// transformation gives it: a depth image of the colour image's size whose pixel holds the z, in
// the colour camera's frame, of the depth pixel that lands there.
//
// Each depth pixel is a square footprint at its own depth (1.2 pixels wide, so neighbours
// overlap): its four corners go through the extrinsics into the colour image and it fills the
// colour pixels whose centres fall inside the corners' bounding box (the colour image is finer than
// the depth image, so single points would leave gaps); where footprints overlap, the nearest wins
// (a z-buffer). A colour pixel gets the depth of one depth pixel or none: nothing is interpolated
// between pixels, so no depth appears across a depth edge, and what the depth camera cannot see
// (beside a near object, parallax) stays 0.
//
//   const DepthImage registered = RegisterDepthToColor(depth, depth_k, color_k, color_from_depth);

#include <Eigen/Geometry>

#include "simtree/io/capture.h"

namespace simtree::synth {

// Throws InputError when `depth` is not of `depth_intrinsics`' size or either intrinsics is
// invalid.
DepthImage RegisterDepthToColor(const DepthImage& depth, const CameraIntrinsics& depth_intrinsics,
                                const CameraIntrinsics& color_intrinsics,
                                const Eigen::Isometry3d& color_from_depth);

}  // namespace simtree::synth
