#pragma once
// The Azure Kinect's colour camera as a camera of its own (`synth --color-size WxH`): its image
// size, its nominal field of view (hardware spec: 90 x 59 degrees in the 16:9 modes, 90 x 74.3 in
// the 4:3 ones) and where it sits against the depth camera. Real recordings are usually processed
// by registering depth into this camera (depth_to_color.h), so the pull stream's colour, depth,
// intrinsics and ground truth are then this camera's.
//
//   const AzureColorCamera color = AzureColorCamera::ForSize(1280, 720);
//   const Eigen::Isometry3d world_from_color = world_from_depth * color.color_from_depth.inverse();
//   const SensorModel renderer = color.RenderModel(depth_sensor);   // RenderRgbd at 1280 x 720

#include <string>

#include <Eigen/Geometry>

#include "simtree/io/capture.h"
#include "simtree/synth/detail/sensor_model.h"

namespace simtree::synth {

struct AzureColorCamera {
  int width = 1280;
  int height = 720;
  double horizontal_fov_deg = 90.0;
  double vertical_fov_deg = 59.0;
  // x_color = color_from_depth * x_depth (metres, OpenCV axes). A real unit's factory
  // calibration (the Azure Kinect recording in the shared data, camera PV0 against D0): the
  // colour camera 32.1 mm to the side of the depth camera, 2.2 mm and 3.9 mm off in y and z, and
  // the depth camera's axis turned 4.9 degrees down against the colour camera's.
  Eigen::Isometry3d color_from_depth = DefaultColorFromDepth();

  // Pinhole intrinsics: square pixels of the geometric mean of the focal lengths the two angles
  // give, the principal point at the image centre (as SensorModel::Intrinsics).
  CameraIntrinsics Intrinsics() const;
  // The renderer's model for this camera's colour: `depth_sensor` with this camera's geometry.
  SensorModel RenderModel(const SensorModel& depth_sensor) const;

  static Eigen::Isometry3d DefaultColorFromDepth();
  // The Azure Kinect's colour modes: 1280x720, 1920x1080, 2560x1440, 3840x2160 (16:9) and
  // 2048x1536, 4096x3072 (4:3). Throws InputError naming `field` for any other size.
  static AzureColorCamera ForSize(int width, int height, const std::string& field = "color_size");
};

}  // namespace simtree::synth
