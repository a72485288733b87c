#include "simtree/synth/detail/rgbd_renderer.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "simtree/synth/detail/sensor_pose.h"
#include "simtree/synth/detail/sensor_random.h"
#include "simtree/synth/detail/textures.h"

namespace simtree::synth {
namespace {

// Surface colour (albedo) of a hit.
Rgb Albedo(const SensorScene& scene, const SceneHit& hit) {
  const SceneOptions& o = scene.options();
  switch (hit.object) {
    case SceneObject::kTree:
      if (hit.marker_index >= 0) {
        const MarkerBand& band = scene.marker_bands()[hit.marker_index];
        return TapeAlbedo(hit.angle, hit.arc_length - 0.5 * (band.begin + band.end),
                          o.texture_seed);
      }
      return BarkAlbedo(BarkPoint{.arc_length_m = hit.arc_length,
                                  .angle_rad = hit.angle,
                                  .radius_m = hit.radius,
                                  .branch = hit.branch},
                        o.texture_seed);
    case SceneObject::kGround:
      return GroundAlbedo(hit.point.x(), hit.point.y(), o.texture_seed);
    case SceneObject::kHedge:
      return HedgeAlbedo(hit.along, hit.point.z(), o.texture_seed);
    case SceneObject::kBox:
      return o.boxes[hit.object_index].albedo *
             (0.9f + 0.2f * ValueNoise(hit.point.x() / 0.05 + hit.point.z() / 0.07,
                                       hit.point.y() / 0.05, o.texture_seed + 3));
    case SceneObject::kPost:
      return Rgb(0.46f, 0.39f, 0.30f) *
             (0.85f + 0.3f * ValueNoise(hit.point.z() / 0.2, hit.object_index, o.texture_seed + 5));
    case SceneObject::kShrub:
      return ShrubAlbedo(hit.along, o.texture_seed + hit.object_index);
    case SceneObject::kRope:
      return RopeAlbedo(hit.along);
    case SceneObject::kNone:
      break;
  }
  return Rgb::Zero();
}

uint8_t ToByte(double value) { return static_cast<uint8_t>(std::clamp(value, 0.0, 255.0) + 0.5); }

}  // namespace

RenderResult RenderRgbd(const SensorScene& scene, const SensorModel& sensor,
                        const Eigen::Isometry3d& world_from_camera, const RenderOptions& options) {
  ValidateSensorModel(sensor, "sensor");
  ValidateCameraPose(world_from_camera, "camera");
  const CameraIntrinsics k = sensor.Intrinsics();
  ValidateIntrinsics(k, "sensor intrinsics");
  const SceneOptions& scene_options = scene.options();
  const Eigen::Vector3d sun = scene_options.sun_direction.normalized();
  const Eigen::Matrix3d rotation = world_from_camera.linear();
  const Eigen::Vector3d origin = world_from_camera.translation();
  const double focal = sensor.FocalLengthPx();

  RenderResult result;
  result.image.intrinsics = k;
  result.image.color = RgbImage(k.width, k.height);
  result.labels = LabelImage(k.width, k.height);
  DepthTruthImage truth(k.width, k.height);

  // Rays go to Embree in packets of 2 x 8 pixels (coherent rays trace faster together), a band
  // of two rows per task.
  constexpr int kTileRows = 2;
  constexpr int kTileColumns = 8;
  const int bands = (k.height + kTileRows - 1) / kTileRows;
  tbb::parallel_for(tbb::blocked_range<int>(0, bands), [&](const tbb::blocked_range<int>& range) {
    std::vector<Eigen::Vector2i> pixels;
    std::vector<Eigen::Vector3d> directions;
    std::vector<SceneHit> hits;
    std::vector<Eigen::Vector3d> shadow_origins;
    std::vector<size_t> shadow_pixels;
    std::vector<uint8_t> shadow_flags, shadowed;
    for (int band = range.begin(); band < range.end(); ++band) {
      pixels.clear();
      directions.clear();
      for (int x0 = 0; x0 < k.width; x0 += kTileColumns) {
        for (int y = band * kTileRows; y < std::min(k.height, (band + 1) * kTileRows); ++y) {
          for (int x = x0; x < std::min(k.width, x0 + kTileColumns); ++x) {
            pixels.emplace_back(x, y);
            // Camera-frame direction with z = 1, so the hit's t is its depth.
            directions.push_back(rotation *
                                 Eigen::Vector3d((x - k.cx) / k.fx, (y - k.cy) / k.fy, 1.0));
          }
        }
      }
      hits.resize(directions.size());
      scene.IntersectCoherent(origin, directions, hits);
      // Shadow rays towards the sun from every hit that faces it, in packets too.
      shadow_origins.clear();
      shadow_pixels.clear();
      for (size_t p = 0; p < hits.size(); ++p) {
        if (options.shadows && hits[p].hit() && hits[p].normal.dot(sun) > 0.0) {
          shadow_origins.push_back(hits[p].point + 1e-4 * hits[p].normal);
          shadow_pixels.push_back(p);
        }
      }
      shadowed.assign(hits.size(), 0);
      shadow_flags.resize(shadow_origins.size());
      scene.OccludedCoherent(shadow_origins, sun, 1e-4, 1e3, shadow_flags);
      for (size_t s = 0; s < shadow_pixels.size(); ++s)
        shadowed[shadow_pixels[s]] = shadow_flags[s];

      for (size_t p = 0; p < pixels.size(); ++p) {
        const int x = pixels[p].x();
        const int y = pixels[p].y();
        const Eigen::Vector3d& direction = directions[p];
        const SceneHit& hit = hits[p];
        PixelLabel& label = result.labels.at(x, y);
        PixelTruth& t = truth.at(x, y);
        Rgb colour;
        if (!hit.hit()) {
          colour = SkyColor(direction);
        } else {
          label.kind = hit.kind;
          label.branch = hit.branch;
          label.marker = hit.marker;
          label.arc_length = static_cast<float>(hit.arc_length);
          label.depth_m = static_cast<float>(hit.t);
          t.depth_m = static_cast<float>(hit.t);
          t.cos_incidence =
              static_cast<float>(std::abs(hit.normal.dot(direction)) / direction.norm());
          if (hit.radius > 0.0) t.width_px = static_cast<float>(2.0 * hit.radius * focal / hit.t);
          double light = scene_options.ambient_intensity;
          const double facing = hit.normal.dot(sun);
          if (facing > 0.0 && !shadowed[p]) light += scene_options.sun_intensity * facing;
          colour = Albedo(scene, hit) * static_cast<float>(light);
        }
        PixelRandom random(options.seed, static_cast<uint64_t>(options.frame),
                           static_cast<uint64_t>(y) * k.width + x, RandomStream::kColor);
        for (int c = 0; c < 3; ++c) {
          result.image.color.at(x, y, c) =
              ToByte(255.0 * colour[c] + sensor.color_noise_std * random.RoughNormal());
        }
      }
    }
  });

  if (!options.measure_depth) {
    result.image.depth = DepthImage(k.width, k.height);
  } else {
    result.measurement =
        MeasureDepth(sensor, truth, {.seed = options.seed, .frame = options.frame});
    result.image.depth = std::move(result.measurement.depth);
    result.measurement.depth = DepthImage();
  }
  if (sensor.blank_color_without_depth && options.measure_depth) {
    for (size_t i = 0; i < result.image.depth.pixels.size(); ++i) {
      if (result.image.depth.pixels[i] == 0) {
        for (int c = 0; c < 3; ++c) result.image.color.pixels[3 * i + c] = 0;
      }
    }
  }
  if (options.marker_boxes) {
    result.markers =
        ComputeMarkerBoxes(scene, k, world_from_camera, result.labels, options.marker_box_options);
  }
  return result;
}

}  // namespace simtree::synth
