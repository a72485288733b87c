#include "simtree/synth/detail/pull_rig.h"

#include "simtree/synth/detail/depth_to_color.h"

namespace simtree::synth {

Eigen::Isometry3d PullRig::WorldFromImage() const {
  return color ? world_from_depth * color->color_from_depth.inverse() : world_from_depth;
}

SensorModel PullRig::ImageSensor() const {
  return color ? color->RenderModel(depth_sensor) : depth_sensor;
}

RenderResult RenderPullRig(const SensorScene& scene, const PullRig& rig,
                           const RenderOptions& options) {
  if (!rig.color) return RenderRgbd(scene, rig.depth_sensor, rig.world_from_depth, options);
  RenderOptions color_options = options;
  color_options.measure_depth = false;
  RenderResult result = RenderRgbd(scene, rig.ImageSensor(), rig.WorldFromImage(), color_options);
  if (!options.measure_depth) return result;
  // The depth camera's own frame: its colour, shadows and marker boxes are not needed.
  RenderOptions depth_options = options;
  depth_options.shadows = false;
  depth_options.marker_boxes = false;
  RenderResult depth = RenderRgbd(scene, rig.depth_sensor, rig.world_from_depth, depth_options);
  result.image.depth = RegisterDepthToColor(depth.image.depth, depth.image.intrinsics,
                                            result.image.intrinsics, rig.color->color_from_depth);
  result.measurement = std::move(depth.measurement);
  if (rig.depth_sensor.blank_color_without_depth) {
    for (size_t i = 0; i < result.image.depth.pixels.size(); ++i) {
      if (result.image.depth.pixels[i] == 0) {
        for (int c = 0; c < 3; ++c) result.image.color.pixels[3 * i + c] = 0;
      }
    }
  }
  return result;
}

}  // namespace simtree::synth
