#include "simtree/synth/detail/azure_color_camera.h"

#include <numbers>

#include <fmt/format.h>

#include "simtree/core/error.h"

namespace simtree::synth {

Eigen::Isometry3d AzureColorCamera::DefaultColorFromDepth() {
  constexpr double kDegree = std::numbers::pi / 180.0;
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  // A point straight ahead of the depth camera lands below the colour image's centre.
  t.linear() = Eigen::AngleAxisd(-4.94 * kDegree, Eigen::Vector3d::UnitX()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(-0.0321, -0.0022, 0.0039);
  return t;
}

CameraIntrinsics AzureColorCamera::Intrinsics() const {
  SensorModel geometry;
  geometry.width = width;
  geometry.height = height;
  geometry.horizontal_fov_deg = horizontal_fov_deg;
  geometry.vertical_fov_deg = vertical_fov_deg;
  return geometry.Intrinsics();
}

SensorModel AzureColorCamera::RenderModel(const SensorModel& depth_sensor) const {
  SensorModel model = depth_sensor;
  model.name = fmt::format("{} colour {}x{}", depth_sensor.name, width, height);
  model.width = width;
  model.height = height;
  model.horizontal_fov_deg = horizontal_fov_deg;
  model.vertical_fov_deg = vertical_fov_deg;
  return model;
}

AzureColorCamera AzureColorCamera::ForSize(int width, int height, const std::string& field) {
  struct Mode {
    int width, height;
    double vertical_fov_deg;
  };
  constexpr Mode kModes[] = {{1280, 720, 59.0},  {1920, 1080, 59.0}, {2560, 1440, 59.0},
                             {3840, 2160, 59.0}, {2048, 1536, 74.3}, {4096, 3072, 74.3}};
  for (const Mode& mode : kModes) {
    if (mode.width == width && mode.height == height) {
      AzureColorCamera camera;
      camera.width = width;
      camera.height = height;
      camera.vertical_fov_deg = mode.vertical_fov_deg;
      return camera;
    }
  }
  throw InputError("synth options", field,
                   fmt::format("expected one of the Azure Kinect's colour sizes 1280x720, "
                               "1920x1080, 2560x1440, 3840x2160, 2048x1536, 4096x3072 (or "
                               "640x576: colour registered to depth), got {}x{}",
                               width, height));
}

}  // namespace simtree::synth
