#pragma once
// A marker's tape band kept over frames: the band is rigid, so its radius in metres does not
// change, and its direction in the image and its foreshortened length change only as the branch
// swings. One frame's blob gives them to within a pixel or so (a band is 3-15 px); the model
// averages the frames where the tape shows whole (the radius over up to 20, the rest over a few)
// and gives the band's box at any centre and depth, also in frames where the tape is partly
// hidden or not seen.

#include "simtree/tracking/detail/band_shape.h"

namespace simtree::tracking::detail {

class BandModel {
 public:
  // Folds in a shape measured on a whole tape at depth `z_m` (> 0).
  void Observe(const BandShape& shape, double z_m);
  bool known() const { return count_ > 0; }
  // The band centred at `center` (px) at depth `z_m`; requires known().
  BandShape At(const Eigen::Vector2d& center, double z_m) const;

 private:
  Eigen::Vector2d axis_ = Eigen::Vector2d::UnitY();
  double half_length_pxm_ = 0.0;  // px at 1 m: px x depth
  double radius_pxm_ = 0.0;
  int count_ = 0;
};

}  // namespace simtree::tracking::detail
