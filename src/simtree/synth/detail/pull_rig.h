#pragma once
// The pull test's camera on its tripod. By default one image: colour registered to the depth
// camera's 640 x 576 pixels. With a colour camera of its own (`synth --color-size`, the way real
// Azure Kinect recordings are usually processed), the colour image is that camera's, rendered
// from where it sits beside the depth camera, and the depth camera's measurement is registered
// into it (depth_to_color.h): the stream's colour, depth, labels, marker boxes, intrinsics and
// ground-truth frame are then all the colour camera's.
//
//   const PullRig rig{.world_from_depth = tripod, .depth_sensor = sensor,
//                     .color = AzureColorCamera::ForSize(1280, 720)};
//   RenderResult frame = RenderPullRig(scene, rig, {.seed = seed, .frame = i});
//   frame.image.intrinsics == rig.Intrinsics();  // colour and depth of that size

#include <optional>

#include <Eigen/Geometry>

#include "simtree/synth/detail/azure_color_camera.h"
#include "simtree/synth/detail/rgbd_renderer.h"

namespace simtree::synth {

struct PullRig {
  Eigen::Isometry3d world_from_depth = Eigen::Isometry3d::Identity();
  SensorModel depth_sensor;
  std::optional<AzureColorCamera> color;  // none: colour registered to depth

  // The camera the stream's images and ground truth are in: the colour camera, or the depth
  // camera when there is none.
  Eigen::Isometry3d WorldFromImage() const;
  // The renderer's model for the stream's colour (the depth sensor's, at the colour geometry).
  SensorModel ImageSensor() const;
  CameraIntrinsics Intrinsics() const { return ImageSensor().Intrinsics(); }
};

// One frame of the stream: colour, labels and (options.marker_boxes) marker boxes from the image
// camera; depth from the depth camera (with the sensor's errors, seeded by options.seed and
// options.frame), registered into the colour camera when there is one; options.measure_depth
// off: no depth render at all, the depth all zero. `measurement` is the depth camera's.
RenderResult RenderPullRig(const SensorScene& scene, const PullRig& rig,
                           const RenderOptions& options);

}  // namespace simtree::synth
