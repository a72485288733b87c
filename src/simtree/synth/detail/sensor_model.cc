#include "simtree/synth/detail/sensor_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "simtree/core/error.h"
#include "simtree/synth/detail/sensor_random.h"

namespace simtree::synth {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

}  // namespace

CameraIntrinsics SensorModel::Intrinsics() const {
  CameraIntrinsics k;
  k.width = width;
  k.height = height;
  k.fx = k.fy = FocalLengthPx();
  k.cx = 0.5 * (width - 1);
  k.cy = 0.5 * (height - 1);
  k.depth_scale_m = 0.001;
  return k;
}

double SensorModel::FocalLengthPx() const {
  const double fx = 0.5 * width / std::tan(0.5 * horizontal_fov_deg * kDegree);
  const double fy = 0.5 * height / std::tan(0.5 * vertical_fov_deg * kDegree);
  return std::sqrt(fx * fy);
}

double SensorModel::DepthNoiseStd(double depth_m, double cos_incidence) const {
  const double c = std::clamp(std::abs(cos_incidence), 0.02, 1.0);
  return (noise_base_m + noise_quadratic_per_m2 * depth_m * depth_m) *
         (1.0 + noise_angle_gain * (1.0 / c - 1.0));
}

double SensorModel::ThinKeepProbability(double width_px) const {
  if (thin_width_px <= 0.0) return 1.0;
  if (thin_softness_px <= 0.0) return width_px >= thin_width_px ? 1.0 : 0.0;
  return 1.0 / (1.0 + std::exp(-(width_px - thin_width_px) / thin_softness_px));
}

double SensorModel::GrazingKeepProbability(double cos_incidence) const {
  const double angle = std::acos(std::clamp(std::abs(cos_incidence), 0.0, 1.0)) / kDegree;
  if (angle <= grazing_start_deg) return 1.0;
  if (angle >= grazing_full_deg) return 0.0;
  return (grazing_full_deg - angle) / (grazing_full_deg - grazing_start_deg);
}

DepthBiasField::DepthBiasField(const SensorModel& sensor)
    : offset_(sensor.bias_offset_m),
      scale_(sensor.bias_scale),
      width_(std::max(sensor.width, 0)),
      height_(std::max(sensor.height, 0)) {
  column_cos_.resize(static_cast<size_t>(width_) * kWaves);
  column_sin_.resize(column_cos_.size());
  row_cos_.resize(static_cast<size_t>(height_) * kWaves);
  row_sin_.resize(row_cos_.size());
  PixelRandom random(sensor.unit_seed, 0, 0, RandomStream::kScene);
  // Each wave: a direction, 0.5-2 cycles across the image, a phase; amplitude bias_pattern_m / 3.
  const double amplitude = sensor.bias_pattern_m / kWaves;
  for (int k = 0; k < kWaves; ++k) {
    const double angle = 2.0 * std::numbers::pi * random.Uniform();
    const double cycles = 0.5 + 1.5 * random.Uniform();
    const double phase = 2.0 * std::numbers::pi * random.Uniform();
    const double a = 2.0 * std::numbers::pi * cycles * std::cos(angle) / std::max(width_, 1);
    const double b = 2.0 * std::numbers::pi * cycles * std::sin(angle) / std::max(height_, 1);
    for (int x = 0; x < width_; ++x) {
      column_cos_[x * kWaves + k] = amplitude * std::cos(a * x);
      column_sin_[x * kWaves + k] = amplitude * std::sin(a * x);
    }
    for (int y = 0; y < height_; ++y) {
      row_cos_[y * kWaves + k] = std::cos(b * y + phase);
      row_sin_[y * kWaves + k] = std::sin(b * y + phase);
    }
  }
}

double DepthBiasField::Pattern(int x, int y) const {
  double sum = 0.0;
  for (int k = 0; k < kWaves; ++k) {
    sum += column_cos_[x * kWaves + k] * row_cos_[y * kWaves + k] -
           column_sin_[x * kWaves + k] * row_sin_[y * kWaves + k];
  }
  return sum;
}

SensorModel SensorModel::AzureKinectNfov() { return SensorModel{}; }

SensorModel SensorModel::Hard() {
  SensorModel s;
  s.name = "azure_kinect_nfov_unbinned_hard";
  s.noise_base_m = 0.003;
  s.noise_quadratic_per_m2 = 0.002;
  s.noise_angle_gain = 1.5;
  s.bias_offset_m = 0.005;
  s.bias_scale = 0.001;
  s.bias_pattern_m = 0.004;
  s.thin_width_px = 2.0;
  s.thin_softness_px = 0.25;
  s.grazing_start_deg = 65.0;
  s.grazing_full_deg = 80.0;
  s.edge_dropout_probability = 0.3;
  s.flying_pixel_probability = 0.6;
  s.outlier_rate = 0.006;
  s.color_noise_std = 4.0;
  return s;
}

SensorModel SensorModel::Ideal() {
  SensorModel s;
  s.name = "ideal";
  s.noise_base_m = 0.0;
  s.noise_quadratic_per_m2 = 0.0;
  s.noise_angle_gain = 0.0;
  s.bias_offset_m = 0.0;
  s.bias_scale = 0.0;
  s.bias_pattern_m = 0.0;
  s.thin_width_px = 0.0;
  s.grazing_start_deg = 90.0;
  s.grazing_full_deg = 90.0;
  s.edge_dropout_probability = 0.0;
  s.flying_pixel_probability = 0.0;
  s.outlier_rate = 0.0;
  s.color_noise_std = 0.0;
  return s;
}

void ValidateSensorModel(const SensorModel& s, const std::string& source) {
  auto fail = [&](const std::string& field, const std::string& expected, double got) {
    throw InputError(source, field, "expected " + expected + ", got " + std::to_string(got));
  };
  if (s.width <= 0) fail("width", "a positive pixel count", s.width);
  if (s.height <= 0) fail("height", "a positive pixel count", s.height);
  const std::pair<const char*, double> finite[] = {
      {"horizontal_fov_deg", s.horizontal_fov_deg},
      {"vertical_fov_deg", s.vertical_fov_deg},
      {"frame_rate_hz", s.frame_rate_hz},
      {"min_range_m", s.min_range_m},
      {"max_range_m", s.max_range_m},
      {"noise_base_m", s.noise_base_m},
      {"noise_quadratic_per_m2", s.noise_quadratic_per_m2},
      {"noise_angle_gain", s.noise_angle_gain},
      {"bias_offset_m", s.bias_offset_m},
      {"bias_scale", s.bias_scale},
      {"bias_pattern_m", s.bias_pattern_m},
      {"quantization_m", s.quantization_m},
      {"thin_width_px", s.thin_width_px},
      {"thin_softness_px", s.thin_softness_px},
      {"grazing_start_deg", s.grazing_start_deg},
      {"grazing_full_deg", s.grazing_full_deg},
      {"edge_jump_m", s.edge_jump_m},
      {"edge_dropout_probability", s.edge_dropout_probability},
      {"flying_pixel_probability", s.flying_pixel_probability},
      {"outlier_rate", s.outlier_rate},
      {"color_noise_std", s.color_noise_std}};
  for (const auto& [field, value] : finite) {
    if (!std::isfinite(value)) fail(field, "a finite number", value);
  }
  for (const auto& [field, value] : {std::pair{"horizontal_fov_deg", s.horizontal_fov_deg},
                                     std::pair{"vertical_fov_deg", s.vertical_fov_deg}}) {
    if (value <= 0.0 || value >= 180.0) fail(field, "an angle in (0, 180) degrees", value);
  }
  if (s.frame_rate_hz <= 0.0) fail("frame_rate_hz", "a positive rate", s.frame_rate_hz);
  if (s.min_range_m <= 0.0) fail("min_range_m", "a positive distance", s.min_range_m);
  if (s.max_range_m <= s.min_range_m) fail("max_range_m", "more than min_range_m", s.max_range_m);
  for (const auto& [field, value] :
       {std::pair{"noise_base_m", s.noise_base_m},
        std::pair{"noise_quadratic_per_m2", s.noise_quadratic_per_m2},
        std::pair{"noise_angle_gain", s.noise_angle_gain},
        std::pair{"bias_pattern_m", s.bias_pattern_m}, std::pair{"thin_width_px", s.thin_width_px},
        std::pair{"thin_softness_px", s.thin_softness_px}, std::pair{"edge_jump_m", s.edge_jump_m},
        std::pair{"color_noise_std", s.color_noise_std}}) {
    if (value < 0.0) fail(field, "a value >= 0", value);
  }
  if (s.quantization_m <= 0.0) fail("quantization_m", "a positive step", s.quantization_m);
  for (const auto& [field, value] :
       {std::pair{"edge_dropout_probability", s.edge_dropout_probability},
        std::pair{"flying_pixel_probability", s.flying_pixel_probability},
        std::pair{"outlier_rate", s.outlier_rate}}) {
    if (value < 0.0 || value > 1.0) fail(field, "a probability in [0, 1]", value);
  }
  if (s.edge_dropout_probability + s.flying_pixel_probability > 1.0) {
    fail("flying_pixel_probability", "at most 1 - edge_dropout_probability",
         s.flying_pixel_probability);
  }
  if (s.grazing_start_deg < 0.0 || s.grazing_start_deg > 90.0) {
    fail("grazing_start_deg", "an angle in [0, 90] degrees", s.grazing_start_deg);
  }
  if (s.grazing_full_deg < s.grazing_start_deg || s.grazing_full_deg > 90.0) {
    fail("grazing_full_deg", "an angle in [grazing_start_deg, 90] degrees", s.grazing_full_deg);
  }
}

}  // namespace simtree::synth
