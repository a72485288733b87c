#pragma once
// A small picture of one view's point cloud as its camera saw it (camera frame: x right, y down),
// points shaded by depth, fitted into the image: the views section shows one per view.

#include <vector>

#include <Eigen/Core>

#include "simtree/io/image_io.h"

namespace simtree::report {

// White background, near points dark green, far points light; an empty cloud gives a blank image.
RgbImage CloudThumbnail(const std::vector<Eigen::Vector3d>& camera_points, int width, int height);

}  // namespace simtree::report
