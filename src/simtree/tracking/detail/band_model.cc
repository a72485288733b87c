#include "simtree/tracking/detail/band_model.h"

#include <algorithm>

namespace simtree::tracking::detail {
namespace {

// Weight of a new frame in the direction and length (they follow the branch's swing within a
// few frames) and the least weight in the radius (a constant, averaged over up to 20 frames).
constexpr double kPoseGain = 0.3;
constexpr double kRadiusMinGain = 0.05;

}  // namespace

void BandModel::Observe(const BandShape& shape, double z_m) {
  Eigen::Vector2d axis = shape.axis;
  if (count_ > 0 && axis.dot(axis_) < 0.0) axis = -axis;  // the same line, the other way round
  if (count_ == 0) {
    axis_ = axis;
    half_length_pxm_ = shape.half_length * z_m;
    radius_pxm_ = shape.radius * z_m;
  } else {
    const double radius_gain = std::max(kRadiusMinGain, 1.0 / (count_ + 1));
    axis_ = ((1.0 - kPoseGain) * axis_ + kPoseGain * axis).normalized();
    half_length_pxm_ += kPoseGain * (shape.half_length * z_m - half_length_pxm_);
    radius_pxm_ += radius_gain * (shape.radius * z_m - radius_pxm_);
  }
  ++count_;
}

BandShape BandModel::At(const Eigen::Vector2d& center, double z_m) const {
  BandShape shape;
  shape.axis = axis_;
  shape.half_length = std::max(0.5, half_length_pxm_ / z_m);
  shape.radius = std::max(0.5, radius_pxm_ / z_m);
  shape.center = center;
  return shape;
}

}  // namespace simtree::tracking::detail
