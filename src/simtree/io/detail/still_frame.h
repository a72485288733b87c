#pragma once
// Scores for picking a scan view's capture: how sharp a colour frame is (variance of the grey
// Laplacian: blur and motion blur lower it) and how much the scene moves between two frames
// (mean absolute grey difference on a 4x smaller image).

#include <vector>

#include "simtree/io/image_io.h"

namespace simtree::azure_detail {

// Grey (0-255) 4x smaller than `color`, each value the mean of a 4x4 block's green channel.
struct SmallGrey {
  int width = 0;
  int height = 0;
  std::vector<float> values;
};
SmallGrey Shrink(const RgbImage& color);

double Sharpness(const RgbImage& color);
// Mean absolute difference; the images must be of one size.
double Motion(const SmallGrey& a, const SmallGrey& b);

// The index of the frame to keep: among frames whose motion is at most the larger of
// `still_motion` and the 25th percentile of `motion`, the sharpest; -1 when there is none.
int PickStill(const std::vector<double>& sharpness, const std::vector<double>& motion,
              double still_motion, int* still_count);

}  // namespace simtree::azure_detail
