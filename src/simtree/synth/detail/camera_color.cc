#include "simtree/synth/detail/camera_color.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "simtree/core/error.h"
#include "simtree/synth/detail/sensor_random.h"

namespace simtree::synth {
namespace {

void Fail(const char* field, const std::string& expected, double got) {
  throw InputError("camera colour options", field,
                   fmt::format("expected {}, got {}", expected, got));
}

// A smooth step from 0 at t <= 0 to 1 at t >= 1.
double SmoothStep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

cv::Mat ToBgrMat(const RgbImage& image) {
  cv::Mat bgr(image.height, image.width, CV_8UC3);
  for (int y = 0; y < image.height; ++y) {
    uint8_t* row = bgr.ptr<uint8_t>(y);
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < 3; ++c) row[3 * x + c] = image.at(x, y, 2 - c);
    }
  }
  return bgr;
}

void FromBgrMat(const cv::Mat& bgr, RgbImage& image) {
  for (int y = 0; y < image.height; ++y) {
    const uint8_t* row = bgr.ptr<uint8_t>(y);
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < 3; ++c) image.at(x, y, 2 - c) = row[3 * x + c];
    }
  }
}

// JPEG round trip of a BGR image. OpenCV's encoder subsamples chroma 4:2:0; for 4:2:2 the rows
// are doubled first (so the vertical halving takes back only the doubling) and averaged in pairs
// after decoding.
cv::Mat JpegRoundTripBgr(const cv::Mat& bgr, int quality, bool chroma_422) {
  cv::Mat input = bgr;
  if (chroma_422) cv::resize(bgr, input, cv::Size(bgr.cols, 2 * bgr.rows), 0, 0, cv::INTER_NEAREST);
  std::vector<uint8_t> bytes;
  if (!cv::imencode(".jpg", input, bytes, {cv::IMWRITE_JPEG_QUALITY, quality})) {
    throw IoError("camera colour: OpenCV could not JPEG-encode a colour frame");
  }
  cv::Mat decoded = cv::imdecode(bytes, cv::IMREAD_COLOR);
  if (decoded.empty())
    throw IoError("camera colour: OpenCV could not decode its own JPEG of a colour frame");
  if (!chroma_422) return decoded;
  cv::Mat out;
  cv::resize(decoded, out, bgr.size(), 0, 0, cv::INTER_AREA);
  return out;
}

}  // namespace

void CameraColorOptions::Validate() const {
  if (!(white_balance_error >= 0 && white_balance_error <= 0.5)) {
    Fail("white_balance_error", "0-0.5", white_balance_error);
  }
  if (!(exposure_drift_stops >= 0 && exposure_drift_stops <= 2)) {
    Fail("exposure_drift_stops", "0-2 EV", exposure_drift_stops);
  }
  if (!(exposure_drift_period_s > 0 && std::isfinite(exposure_drift_period_s))) {
    Fail("exposure_drift_period_s", "a period > 0 s", exposure_drift_period_s);
  }
  for (const ExposureStep& step : exposure_steps) {
    if (!std::isfinite(step.time_s)) Fail("exposure_steps.time_s", "a finite time", step.time_s);
    if (!(std::abs(step.stops) <= 4)) Fail("exposure_steps.stops", "-4 to 4 EV", step.stops);
    if (!(step.ramp_s > 0 && step.ramp_s <= 60))
      Fail("exposure_steps.ramp_s", "0-60 s", step.ramp_s);
  }
  if (!(read_noise_std >= 0 && read_noise_std <= 50)) {
    Fail("read_noise_std", "0-50 levels", read_noise_std);
  }
  if (!(shot_noise_gain >= 0 && shot_noise_gain <= 10)) {
    Fail("shot_noise_gain", "0-10 levels", shot_noise_gain);
  }
  if (!(defocus_sigma_px >= 0 && defocus_sigma_px <= 10)) {
    Fail("defocus_sigma_px", "0-10 px", defocus_sigma_px);
  }
  if (jpeg_quality < 0 || jpeg_quality > 100) Fail("jpeg_quality", "0-100", jpeg_quality);
}

CameraColorOptions CameraColorOptions::WithExposureStep(double time_s) {
  CameraColorOptions options;
  options.exposure_steps.push_back({.time_s = time_s, .stops = -0.8, .ramp_s = 0.4});
  return options;
}

CameraColor::CameraColor(const CameraColorOptions& options, uint64_t seed)
    : options_(options), seed_(seed) {
  options_.Validate();
  PixelRandom random(seed, 0, 0, RandomStream::kCamera);
  white_balance_[0] = std::exp(options_.white_balance_error * random.Normal());
  white_balance_[2] = std::exp(options_.white_balance_error * random.Normal());
  drift_phase_[0] = 2.0 * std::numbers::pi * random.Uniform();
  drift_phase_[1] = 2.0 * std::numbers::pi * random.Uniform();
}

double CameraColor::ExposureGain(double time_s) const {
  const double w = 2.0 * std::numbers::pi / options_.exposure_drift_period_s;
  // A slow swing and a faster, smaller one (the auto-exposure hunting), starting wherever the
  // phases put them.
  double stops =
      options_.exposure_drift_stops * (0.75 * std::sin(w * time_s + drift_phase_[0]) +
                                       0.25 * std::sin(2.7 * w * time_s + drift_phase_[1]));
  for (const ExposureStep& step : options_.exposure_steps) {
    stops += step.stops * SmoothStep((time_s - step.time_s) / step.ramp_s);
  }
  return std::exp2(stops);
}

void CameraColor::Apply(double time_s, int64_t frame, RgbImage& image) const {
  if (image.empty()) return;
  const double exposure = ExposureGain(time_s);
  // Light on the sensor (levels, unclipped), channels B, G, R.
  cv::Mat light(image.height, image.width, CV_32FC3);
  float gain[3];
  for (int c = 0; c < 3; ++c) gain[c] = static_cast<float>(exposure * white_balance_[2 - c]);
  tbb::parallel_for(0, image.height, [&](int y) {
    float* row = light.ptr<float>(y);
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < 3; ++c) row[3 * x + c] = gain[c] * image.at(x, y, 2 - c);
    }
  });
  if (options_.defocus_sigma_px > 0) {
    cv::GaussianBlur(light, light, cv::Size(0, 0), options_.defocus_sigma_px);
  }
  cv::Mat bgr(image.height, image.width, CV_8UC3);
  tbb::parallel_for(0, image.height, [&](int y) {
    const float* in = light.ptr<float>(y);
    uint8_t* out = bgr.ptr<uint8_t>(y);
    for (int x = 0; x < image.width; ++x) {
      PixelRandom random(seed_, static_cast<uint64_t>(frame),
                         static_cast<uint64_t>(y) * image.width + x, RandomStream::kCamera);
      for (int c = 0; c < 3; ++c) {
        const double level = in[3 * x + c];
        const double sigma = std::sqrt(options_.read_noise_std * options_.read_noise_std +
                                       options_.shot_noise_gain * std::max(level, 0.0));
        const double noisy = level + sigma * random.RoughNormal();
        out[3 * x + c] = static_cast<uint8_t>(std::clamp(noisy, 0.0, 255.0) + 0.5);
      }
    }
  });
  if (options_.jpeg_quality > 0) {
    bgr = JpegRoundTripBgr(bgr, options_.jpeg_quality, options_.chroma_422);
  }
  FromBgrMat(bgr, image);
}

RgbImage JpegRoundTrip(const RgbImage& image, int quality, bool chroma_422) {
  if (quality < 1 || quality > 100) {
    throw InputError("JpegRoundTrip", "quality", fmt::format("expected 1-100, got {}", quality));
  }
  RgbImage out(image.width, image.height);
  if (image.empty()) return out;
  FromBgrMat(JpegRoundTripBgr(ToBgrMat(image), quality, chroma_422), out);
  return out;
}

}  // namespace simtree::synth
