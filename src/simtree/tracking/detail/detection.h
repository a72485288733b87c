#pragma once
// What one tape blob says about its marker: the sub-pixel centre (the centroid of its pixels and
// their mixed ring, each weighted by its share of tape, TapeCoverage), the band's shape and box
// (band_shape.h), and the marker's 3D centre on the branch axis.
//
// 3D centre: a low quantile (`depth_quantile`) of the depths of the blob's clean tape pixels,
// after dropping pixels on a depth edge (a 4-neighbour more than `edge_m` away: flying pixels
// between the tape and what is behind it) and pixels far from their median: the front of the
// branch, since a sensor mixes the depth of a tape a few pixels wide with what lies behind it. The
// branch axis lies one branch radius behind the front (`axis_offset_ratio`), the radius read from
// the blob's width across the branch. Both were chosen on synth streams (docs/tracking.md).

#include <array>
#include <vector>

#include <Eigen/Core>

#include "simtree/io/capture.h"
#include "simtree/tracking/detail/band_shape.h"
#include "simtree/tracking/detail/blob_detector.h"

namespace simtree::tracking::detail {

struct MeasureOptions {
  double edge_m = 0.03;  // depth step that marks a depth edge
  // Variance (px^2, x and y) the colour camera's blur adds to a tape's extent, taken off the
  // band's (band_shape.h). 0: on synth's camera colour (MJPEG 4:2:2 chroma, defocus) a uniform
  // 0.45 px^2 across rows narrowed boxes too wide on some streams and too narrow on others (the
  // bias is each tape's colour, not the camera's), so no blur is assumed.
  Eigen::Vector2d blur_var_px2 = Eigen::Vector2d::Zero();
  double axis_offset_ratio = 1.0;  // axis behind the measured front, in branch radii
  double depth_quantile = 0.25;    // quantile of the tape's depths taken as its front
};

struct Detection {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  // px
  BandShape shape;                                   // the band it shows, centred at `center`
  double weight = 0.0;  // summed tape weight (about the tape's visible area, px)
  int pixel_count = 0;  // tape pixels
  int source = 0;       // Blob::source: detections split from one blob share it
  bool has_depth = false;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // camera frame, m (when has_depth)
  double radius_m = 0.0;                               // branch radius estimate
  double front_m = 0.0;                                // the measured front's depth (m)
  std::vector<double> depths_m;                        // the clean tape pixels' depths, sorted (m)
  double depth_quantile = 0.25;                        // the quantile taken as the front
  // The branch's axis point from the depths of the blob and its ring, when the tape itself has
  // few depth pixels (a second reading for RemeasureNear).
  bool has_branch_depth = false;
  Eigen::Vector3d branch_position = Eigen::Vector3d::Zero();

  std::array<double, 4> Box() const { return shape.Box(); }
};

// Measures a blob of the last frame `detector` searched.
Detection MeasureBlob(const Blob& blob, const RgbdImage& image, BlobDetector& detector,
                      const MeasureOptions& options);

// The share of each pixel of `blob` (its pixels, then its ring) covered by tape, from the tape's
// chroma: 1 at the blob's typical tape pixel, 0 at its background (the median of the ring pixels
// with no tape colour).
std::vector<double> TapeCoverage(const Blob& blob, const RgbImage& color, BlobDetector& detector);

// The 3D centre measured again from only the tape depths that agree (within `window_m`) with a
// predicted axis depth `z_axis`: what a marker partly hidden behind a twig, whose tape pixels mix
// their depth with the twig's, still says about itself; failing that, the branch's reading
// (`branch_position`) when it lies within `window_m`. False when neither agrees.
bool RemeasureNear(const Detection& det, const CameraIntrinsics& intrinsics, double z_axis,
                   double window_m, Eigen::Vector3d* position);

// Robust depth (m) of `pixels` of `depth`, the `quantile` of their depths once depth edges and
// outliers are dropped: 0 when none has a usable measurement.
double RobustDepth(const DepthImage& depth, double depth_scale_m, const std::vector<int>& pixels,
                   double edge_m, double quantile = 0.5);

}  // namespace simtree::tracking::detail
