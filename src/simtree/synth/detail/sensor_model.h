#pragma once
// The virtual Azure Kinect: geometry and measurement errors of its depth camera in NFOV unbinned
// mode (640 x 576, about 75 x 65 degrees, 30 fps, 0.5-3.86 m) with a colour image registered to
// the depth pixels. Every error is a named field; docs/sensor.md gives the source or the reason for
// each default. `Hard()` is an outdoor-sunlight variant with more of every error.
//
// The depth a pixel reports (sensor_measurement.h applies it, in this order):
//   no surface, or a surface outside [min_range_m, max_range_m] along the ray  -> 0
//   a thin curve (twig, rope) of projected width w px is kept with ThinKeepProbability(w)
//   a surface seen at incidence theta is kept with GrazingKeepProbability(cos theta)
//   on a depth discontinuity: dropped, or a "flying pixel" between the near and the far surface
//   z + DepthBiasField::At(z, pixel) + DepthNoiseStd(z, cos theta) N(0, 1), quantised,
//   range-checked any pixel, surface or sky, may instead be a sparse outlier at a random depth in
//   range

#include <cstdint>
#include <string>
#include <vector>

#include "simtree/io/capture.h"

namespace simtree::synth {

struct SensorModel {
  std::string name = "azure_kinect_nfov_unbinned";

  // ---- Geometry
  int width = 640;
  int height = 576;
  // Nominal field of view. The pinhole used here has square pixels whose focal length is the
  // geometric mean of the two the angles give, so the image spans 72.8 x 67.1 degrees.
  double horizontal_fov_deg = 75.0;
  double vertical_fov_deg = 65.0;
  double frame_rate_hz = 30.0;
  double min_range_m = 0.5;   // along the ray
  double max_range_m = 3.86;  // along the ray

  // ---- Random depth error: sigma = (noise_base_m + noise_quadratic_per_m2 z^2)
  //                                 * (1 + noise_angle_gain (1 / cos theta - 1))
  double noise_base_m = 0.0015;
  double noise_quadratic_per_m2 = 0.001;  // metres per square metre of depth
  double noise_angle_gain = 1.0;

  // ---- Systematic depth error: offset + scale z + a smooth fixed pattern over the image of
  // amplitude `bias_pattern_m`, drawn once per unit from `unit_seed` (same for every frame).
  double bias_offset_m = 0.002;
  double bias_scale = 0.0005;  // fraction of the depth
  double bias_pattern_m = 0.002;
  uint64_t unit_seed = 1;

  double quantization_m = 0.001;  // the depth PNG holds millimetres

  // ---- Dropout of thin curves: kept with probability 1 / (1 + exp(-(w - thin_width_px) /
  // thin_softness_px)) for a projected width w = 2 r f / z pixels.
  double thin_width_px = 1.5;
  double thin_softness_px = 0.15;

  // ---- Dropout at grazing incidence: always kept below grazing_start_deg, never above
  // grazing_full_deg, linear in the angle between.
  double grazing_start_deg = 75.0;
  double grazing_full_deg = 85.0;

  // ---- Depth discontinuities: a pixel with a surface whose 4-neighbour is more than edge_jump_m
  // nearer or farther, or has no return at all, is an edge pixel. It is dropped with
  // edge_dropout_probability; when the neighbour is a surface in range it is instead a flying
  // pixel with flying_pixel_probability: its depth moves a uniform fraction in [0, 0.5) of the way
  // to the neighbour's (the pixel's footprint straddles both surfaces; its centre is on its own).
  double edge_jump_m = 0.05;
  double edge_dropout_probability = 0.2;
  double flying_pixel_probability = 0.5;

  // ---- Sparse outliers (sunlight): share of all pixels that report a uniform random depth.
  double outlier_rate = 0.002;

  // ---- Colour
  double color_noise_std = 2.0;  // 8-bit levels, per channel
  // The SDK's colour-to-depth transformation gives no colour where there is no depth; off by
  // default so a person (and a colour tracker) sees the sky and the twigs the depth lost.
  bool blank_color_without_depth = false;

  // Pinhole intrinsics of the depth image (and of the colour image registered to it).
  CameraIntrinsics Intrinsics() const;
  double FocalLengthPx() const;

  double DepthNoiseStd(double depth_m, double cos_incidence) const;
  double ThinKeepProbability(double width_px) const;
  double GrazingKeepProbability(double cos_incidence) const;

  // The defaults above: an Azure Kinect in NFOV unbinned mode outdoors in winter shade.
  static SensorModel AzureKinectNfov();
  // More of every error: low sun, a dirty window, a warm sensor.
  static SensorModel Hard();
  // No error at all (exact depth, quantised; thin curves and grazing surfaces kept): for ground
  // truth and tests.
  static SensorModel Ideal();
};

// The systematic depth error of a sensor at every pixel: offset + scale z + the unit's fixed
// pattern (three low-frequency waves across the image, drawn from `unit_seed`, scaled to
// bias_pattern_m). Tables per row and column make it cheap per pixel.
class DepthBiasField {
 public:
  explicit DepthBiasField(const SensorModel& sensor);
  // Metres added to a true depth `depth_m` at pixel (x, y).
  double At(double depth_m, int x, int y) const {
    return offset_ + scale_ * depth_m + Pattern(x, y);
  }
  // The fixed pattern alone (in [-bias_pattern_m, bias_pattern_m]).
  double Pattern(int x, int y) const;

 private:
  static constexpr int kWaves = 3;
  double offset_ = 0.0;
  double scale_ = 0.0;
  int width_ = 0;
  int height_ = 0;
  // cos(a x + b y + phase) = cos(a x) cos(b y + phase) - sin(a x) sin(b y + phase).
  std::vector<double> column_cos_, column_sin_;  // width x kWaves
  std::vector<double> row_cos_, row_sin_;        // height x kWaves
};

// Throws InputError naming `source` and the field for a size that is not positive, a value that
// is not finite, a probability outside [0, 1], a range with min >= max, angles out of order.
void ValidateSensorModel(const SensorModel& sensor, const std::string& source);

}  // namespace simtree::synth
