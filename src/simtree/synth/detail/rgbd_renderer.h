#pragma once
// The virtual Azure Kinect's frame: one ray per pixel through the scene (sensor_scene.h), the
// exact hits turned into a colour image (procedural textures, a sun with cast shadows and an
// ambient term, mild noise) and a depth image with the sensor's errors (sensor_measurement.h),
// plus per-pixel labels and the tape markers' boxes for ground truth.
//
// Deterministic: the noise of a pixel depends only on (seed, frame, pixel), so the same inputs
// give the same bytes whatever the number of threads.
//
//   SensorModel sensor = SensorModel::AzureKinectNfov();
//   SensorScene scene(tree, DefaultSceneOptions(tree, seed));
//   scene.SetPose(pose);
//   RenderResult r = RenderRgbd(scene, sensor, world_from_camera, {.seed = seed, .frame = i});
//   WritePng(r.image.color, ...); WritePng(r.image.depth, ...); r.markers[k].box ...

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "simtree/io/capture.h"
#include "simtree/synth/detail/marker_boxes.h"
#include "simtree/synth/detail/rgbd_labels.h"
#include "simtree/synth/detail/sensor_measurement.h"
#include "simtree/synth/detail/sensor_model.h"
#include "simtree/synth/detail/sensor_scene.h"

namespace simtree::synth {

struct RenderOptions {
  uint64_t seed = 0;
  int64_t frame = 0;
  // Sun shadows in the colour image (one more ray per lit pixel).
  bool shadows = true;
  // Compute RenderResult::markers (boxes and visibility of the tape bands).
  bool marker_boxes = true;
  // Measure depth (sensor_measurement.h); off: image.depth is all zero (a colour-only render).
  bool measure_depth = true;
  MarkerBoxOptions marker_box_options = {};
};

struct RenderResult {
  RgbdImage image;  // colour RGB8 and depth uint16 mm, registered; the sensor's intrinsics
  LabelImage labels;
  std::vector<MarkerObservation> markers;  // per tree marker, when options.marker_boxes
  // What happened to every depth pixel and how often (its `depth` is moved into image.depth).
  MeasureResult measurement;
};

// Throws InputError for a sensor model that does not validate, a camera pose that is not a finite
// rigid transform.
RenderResult RenderRgbd(const SensorScene& scene, const SensorModel& sensor,
                        const Eigen::Isometry3d& world_from_camera,
                        const RenderOptions& options = {});

}  // namespace simtree::synth
