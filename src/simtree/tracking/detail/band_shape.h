#pragma once
// The projection of a tape band (a short cylinder of the branch's radius, as long as the tape is
// wide) read from the pixels of its blob, and the box of the whole band.
//
// Seen from the side a band projects to a rectangle: the branch's diameter across, the tape's
// width along the branch (foreshortened). The blob's weighted moments give it: the principal axis
// is the branch's direction in the image, and a uniform interval of half-length a has variance
// a^2 / 3. A known colour blur of the camera (defocus, MJPEG's chroma at half the width: the tape
// is found by its chroma) adds its own variance to the blob's and can be taken off.

#include <array>
#include <vector>

#include <Eigen/Core>

namespace simtree::tracking::detail {

struct BandShape {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // px
  Eigen::Vector2d axis = Eigen::Vector2d::UnitY();   // unit, along the branch
  double half_length = 0.5;                          // along the branch (px)
  double radius = 0.5;                               // across it: the branch's radius (px)

  // The box [x, y, w, h] of the rectangle.
  std::array<double, 4> Box() const;
};

// The band's shape from weighted pixel positions (the blob's pixels and ring, each weighted by its
// share of tape), with `blur_var_px2` the camera's colour blur (variance in x and y, px^2). The
// weights must not all be 0.
BandShape MeasureBandShape(const std::vector<Eigen::Vector2d>& points,
                           const std::vector<double>& weights, const Eigen::Vector2d& blur_var_px2);

}  // namespace simtree::tracking::detail
