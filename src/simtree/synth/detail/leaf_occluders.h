#pragma once
// Leaves on twigs near the pull camera, swinging in the wind in front of the markers (`synth
// --hard`): each leaf is an ellipse at a fixed distance from the camera that swings to and fro
// across one marker's place in the first frame, so the tape is hidden part of the time and the
// tracker must coast through it. Drawn into a rendered frame before the marker boxes are
// computed: colour (a shaded green), depth (the leaf's distance, 1 mm steps) and labels (no
// longer the tape), so gt/markers_2d.json's `visible` follows what the camera sees.
//
// They are painted in the image, not traced: they cast no shadow and the depth sensor's
// silhouette errors (flying pixels, dropout) do not touch their edges.
//
//   const std::vector<LeafOccluder> leaves = PlanLeafOccluders(first_frame_boxes, {.seed = s});
//   DrawLeafOccluders(leaves, time_s, intrinsics, rendered);   // before ComputeMarkerBoxes

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "simtree/io/capture.h"
#include "simtree/io/ground_truth.h"
#include "simtree/synth/detail/rgbd_labels.h"

namespace simtree::synth {

struct LeafOccluder {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();      // middle of the swing, px
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  // of the swing, unit
  double amplitude_px = 30.0;
  double period_s = 2.0;
  double phase_rad = 0.0;
  double half_length_px = 10.0, half_width_px = 5.0;           // the ellipse's semi-axes
  double depth_m = 1.0;                                        // distance from the camera (z)
  Eigen::Vector3f color = Eigen::Vector3f(0.2f, 0.35f, 0.1f);  // linear RGB, 0-1
  // Where the leaf is at `time_s`.
  Eigen::Vector2d CentreAt(double time_s) const;
};

struct LeafOccluderOptions {
  int count = 3;  // leaves, each over another marker where there are enough
  uint64_t seed = 0;
  // Image pixels per pixel of the 640 x 576 image the leaves' sizes and swings are given for
  // (a colour camera's focal length over the depth camera's), so they span the same angles.
  double pixel_scale = 1.0;
  void Validate() const;  // throws InputError naming the field
};

// Leaves over markers visible in `first_frame` (none when no marker is visible).
std::vector<LeafOccluder> PlanLeafOccluders(const MarkerFrame2d& first_frame,
                                            const LeafOccluderOptions& options = {});

// Paints the leaves at `time_s` into colour, depth and labels (all of the intrinsics' size).
void DrawLeafOccluders(const std::vector<LeafOccluder>& leaves, double time_s, RgbImage& color,
                       DepthImage& depth, LabelImage& labels);

}  // namespace simtree::synth
