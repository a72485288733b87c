#pragma once
// Ground truth of the tape markers in one rendered frame (gt/markers_2d.json): per marker the box
// of the projection of its whole tape band (clipped to the image), how many of its pixels the
// camera sees, and which share of the band that is once occluders are taken into account.
//
// The box bounds the band's rims (and the joints of the branch inside the band) projected through
// the pinhole, grown by the polygon and joint margins, so every pixel whose centre sees the band
// lies inside it. The band's unoccluded pixels are counted by tracing every pixel of the box
// against the band's own branch alone (SensorScene::IntersectMarkerBand); the visible ones are
// the pixels the label image gives to the marker.

#include <vector>

#include <Eigen/Geometry>

#include "simtree/io/capture.h"
#include "simtree/io/ground_truth.h"
#include "simtree/synth/detail/rgbd_labels.h"
#include "simtree/synth/detail/sensor_scene.h"

namespace simtree::synth {

struct MarkerBoxOptions {
  // A marker is `visible` (a tracker should find it) when at least this share of its band's
  // unoccluded pixels shows and at least this many pixels do.
  double min_visible_fraction = 0.3;
  int min_visible_pixels = 5;
};

struct MarkerObservation {
  MarkerBox2d box;  // id, visible, visible_fraction, visible_pixels, box [x, y, w, h]
  Eigen::Vector3d center_camera = Eigen::Vector3d::Zero();  // on the branch axis, camera frame
  int band_pixels = 0;  // the band's pixels if nothing occluded it
};

// One observation per tree marker, in tree.markers order (all-zero boxes when the scene has no
// tape bands). `labels` must be the frame rendered with the same scene, intrinsics and pose.
std::vector<MarkerObservation> ComputeMarkerBoxes(const SensorScene& scene,
                                                  const CameraIntrinsics& intrinsics,
                                                  const Eigen::Isometry3d& world_from_camera,
                                                  const LabelImage& labels,
                                                  const MarkerBoxOptions& options = {});

}  // namespace simtree::synth
