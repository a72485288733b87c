#include "simtree/synth/detail/sensor_measurement.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "simtree/core/error.h"
#include "simtree/synth/detail/sensor_random.h"

namespace simtree::synth {
namespace {

constexpr int kEffectCount = static_cast<int>(DepthEffect::kOutlier) + 1;

// The largest depth jump to a 4-neighbour, and whether a neighbour returns nothing.
struct EdgeInfo {
  bool is_edge = false;
  bool neighbour_is_surface = false;  // the biggest jump is to a surface in range
  double neighbour_depth = 0.0;
};

EdgeInfo FindEdge(const DepthTruthImage& truth, const std::vector<uint8_t>& returns, int x, int y,
                  double depth, double jump_m) {
  EdgeInfo edge;
  double biggest = jump_m;
  const int dx[] = {1, -1, 0, 0};
  const int dy[] = {0, 0, 1, -1};
  for (int k = 0; k < 4; ++k) {
    const int nx = x + dx[k];
    const int ny = y + dy[k];
    if (nx < 0 || ny < 0 || nx >= truth.width || ny >= truth.height) continue;
    const size_t n = static_cast<size_t>(ny) * truth.width + nx;
    if (!returns[n]) {
      edge.is_edge = true;  // next to sky or to a surface out of range: no mixing, maybe a drop
      continue;
    }
    const double jump = std::abs(truth.pixels[n].depth_m - depth);
    if (jump > biggest) {
      biggest = jump;
      edge.is_edge = true;
      edge.neighbour_is_surface = true;
      edge.neighbour_depth = truth.pixels[n].depth_m;
    }
  }
  return edge;
}

}  // namespace

const char* ToString(DepthEffect effect) {
  switch (effect) {
    case DepthEffect::kMeasured:
      return "measured";
    case DepthEffect::kNoReturn:
      return "no_return";
    case DepthEffect::kOutOfRange:
      return "out_of_range";
    case DepthEffect::kThinDropout:
      return "thin_dropout";
    case DepthEffect::kGrazingDropout:
      return "grazing_dropout";
    case DepthEffect::kEdgeDropout:
      return "edge_dropout";
    case DepthEffect::kFlyingPixel:
      return "flying_pixel";
    case DepthEffect::kOutlier:
      return "outlier";
  }
  return "unknown";
}

namespace {

// Ray length per unit of depth at a pixel: sqrt(1 + a^2 + b^2), a and b its normalised offsets.
class RayScale {
 public:
  RayScale(const CameraIntrinsics& k, int width, int height) : a2_(width), b2_(height) {
    for (int x = 0; x < width; ++x) a2_[x] = ((x - k.cx) / k.fx) * ((x - k.cx) / k.fx);
    for (int y = 0; y < height; ++y) b2_[y] = ((y - k.cy) / k.fy) * ((y - k.cy) / k.fy);
  }
  double operator()(int x, int y) const { return std::sqrt(1.0 + a2_[x] + b2_[y]); }

 private:
  std::vector<double> a2_, b2_;
};

void CheckTruthSize(const SensorModel& sensor, const DepthTruthImage& truth) {
  if (truth.width != sensor.width || truth.height != sensor.height ||
      truth.pixels.size() != static_cast<size_t>(truth.width) * truth.height) {
    throw InputError("<memory>", "depth truth",
                     "expected a " + std::to_string(sensor.width) + "x" +
                         std::to_string(sensor.height) + " image, got " +
                         std::to_string(truth.width) + "x" + std::to_string(truth.height) +
                         " with " + std::to_string(truth.pixels.size()) + " pixels");
  }
}

// Which pixels see a surface whose true distance along the ray is in range (a return). Throws on
// the first pixel (by row) whose true depth is not a finite number >= 0.
std::vector<uint8_t> FindReturns(const SensorModel& sensor, const DepthTruthImage& truth,
                                 const RayScale& ray_scale) {
  const int w = truth.width;
  const int h = truth.height;
  std::vector<uint8_t> returns(truth.pixels.size(), 0);
  std::vector<int> bad_row(h, -1);  // first bad pixel's column per row
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * w + x;
      const float z = truth.pixels[i].depth_m;
      if (!std::isfinite(z) || z < 0.0f) {
        if (bad_row[y] < 0) bad_row[y] = x;
        continue;
      }
      const double range = z * ray_scale(x, y);
      returns[i] = z > 0.0f && range >= sensor.min_range_m && range <= sensor.max_range_m;
    }
  });
  for (int y = 0; y < h; ++y) {
    if (bad_row[y] < 0) continue;
    throw InputError(
        "<memory>",
        "depth truth pixel (" + std::to_string(bad_row[y]) + ", " + std::to_string(y) + ")",
        "expected a finite depth >= 0, got " + std::to_string(truth.at(bad_row[y], y).depth_m));
  }
  return returns;
}

// What the sensor reads at one pixel, and why.
struct PixelReading {
  DepthEffect effect = DepthEffect::kMeasured;
  uint16_t value = 0;  // depth image units, 0 = no measurement
};

// The image and sensor a pixel is measured in.
struct MeasureContext {
  const SensorModel& sensor;
  const DepthTruthImage& truth;
  const std::vector<uint8_t>& returns;
  const CameraIntrinsics& k;
  const DepthBiasField& bias;
  const RayScale& ray_scale;
};

PixelReading MeasurePixel(const MeasureContext& c, int x, int y, PixelRandom& random) {
  const SensorModel& sensor = c.sensor;
  const size_t i = static_cast<size_t>(y) * c.truth.width + x;
  const PixelTruth& t = c.truth.pixels[i];
  // One number per decision, always drawn in this order, so changing one effect's probability
  // leaves the others' draws alone.
  const double u_outlier = random.Uniform();
  const double u_outlier_range = random.Uniform();
  const double u_thin = random.Uniform();
  const double u_grazing = random.Uniform();
  const double u_edge = random.Uniform();
  const double u_mix = random.Uniform();
  const double u_gauss1 = random.Uniform();
  const double u_gauss2 = random.Uniform();

  PixelReading reading;
  double z = t.depth_m;
  if (t.depth_m <= 0.0f) {
    reading.effect = DepthEffect::kNoReturn;
  } else if (!c.returns[i]) {
    reading.effect = DepthEffect::kOutOfRange;
  } else if (t.width_px > 0.0f && u_thin >= sensor.ThinKeepProbability(t.width_px)) {
    reading.effect = DepthEffect::kThinDropout;
  } else if (u_grazing >= sensor.GrazingKeepProbability(t.cos_incidence)) {
    reading.effect = DepthEffect::kGrazingDropout;
  } else {
    const EdgeInfo edge = FindEdge(c.truth, c.returns, x, y, z, sensor.edge_jump_m);
    if (edge.is_edge && u_edge < sensor.edge_dropout_probability) {
      reading.effect = DepthEffect::kEdgeDropout;
    } else if (edge.is_edge && edge.neighbour_is_surface &&
               u_edge < sensor.edge_dropout_probability + sensor.flying_pixel_probability) {
      reading.effect = DepthEffect::kFlyingPixel;
      z += 0.5 * u_mix * (edge.neighbour_depth - z);
    }
  }
  if (reading.effect == DepthEffect::kMeasured || reading.effect == DepthEffect::kFlyingPixel) {
    const double sigma = sensor.DepthNoiseStd(z, t.cos_incidence);
    const double noise =
        sigma > 0.0 ? sigma * PixelRandom::NormalFromUniforms(u_gauss1, u_gauss2) : 0.0;
    const double measured = z + c.bias.At(z, x, y) + noise;
    const double quantized = std::round(measured / sensor.quantization_m) * sensor.quantization_m;
    const double range = quantized * c.ray_scale(x, y);
    if (range < sensor.min_range_m || range > sensor.max_range_m) {
      reading.effect = DepthEffect::kOutOfRange;
    } else {
      reading.value = static_cast<uint16_t>(std::lround(quantized / c.k.depth_scale_m));
    }
  }
  if (u_outlier < sensor.outlier_rate) {
    reading.effect = DepthEffect::kOutlier;
    const double scale = c.ray_scale(x, y);
    const double range =
        sensor.min_range_m + (sensor.max_range_m - sensor.min_range_m) * u_outlier_range;
    // Floor, not round: the outlier must stay inside the range after quantisation.
    reading.value =
        static_cast<uint16_t>(std::max(1.0, std::floor(range / scale / c.k.depth_scale_m)));
    if (reading.value * c.k.depth_scale_m * scale < sensor.min_range_m) {
      reading.value =
          static_cast<uint16_t>(std::ceil(sensor.min_range_m / scale / c.k.depth_scale_m));
    }
  }
  return reading;
}

}  // namespace

MeasureResult MeasureDepth(const SensorModel& sensor, const DepthTruthImage& truth,
                           const MeasureOptions& options) {
  ValidateSensorModel(sensor, "sensor");
  CheckTruthSize(sensor, truth);
  const CameraIntrinsics k = sensor.Intrinsics();
  const int w = truth.width;
  const int h = truth.height;
  const DepthBiasField bias(sensor);
  const RayScale ray_scale(k, w, h);
  const std::vector<uint8_t> returns = FindReturns(sensor, truth, ray_scale);
  const MeasureContext context{sensor, truth, returns, k, bias, ray_scale};

  MeasureResult result;
  result.depth = DepthImage(w, h, 0);
  result.effects.assign(truth.pixels.size(), DepthEffect::kMeasured);
  std::vector<std::array<int64_t, kEffectCount>> row_counts(h);
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      auto& counts = row_counts[y];
      counts.fill(0);
      for (int x = 0; x < w; ++x) {
        const size_t i = static_cast<size_t>(y) * w + x;
        PixelRandom random(options.seed, static_cast<uint64_t>(options.frame), i,
                           RandomStream::kDepth);
        const PixelReading reading = MeasurePixel(context, x, y, random);
        result.depth.pixels[i] = reading.value;
        result.effects[i] = reading.effect;
        ++counts[static_cast<size_t>(reading.effect)];
      }
    }
  });

  result.counts.assign(kEffectCount, 0);
  for (const auto& row : row_counts) {
    for (int e = 0; e < kEffectCount; ++e) result.counts[e] += row[e];
  }
  return result;
}

}  // namespace simtree::synth
