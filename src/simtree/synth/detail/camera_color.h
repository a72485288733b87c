#pragma once
// Colour as a real RGB camera delivers it, applied to the renderer's clean colour: white balance
// off by a little, auto-exposure drifting through the record (and, for --hard, stepping when the
// light changes), photon and read noise, slight defocus, and MJPEG compression (JPEG through
// OpenCV with the chroma halved horizontally, 4:2:2, as the Azure Kinect's colour camera sends
// it). The renderer's colour has none of these: thin red tape stays saturated to its last pixel.
//
// Deterministic: the white balance and the drift are drawn once per capture from the seed, a
// pixel's noise depends only on (seed, frame, pixel).
//
//   const CameraColor camera(CameraColorOptions{}, seed);
//   camera.Apply(frame_time_s, frame_index, rendered.image.color);

#include <array>
#include <cstdint>
#include <vector>

#include "simtree/io/image_io.h"

namespace simtree::synth {

// A change of the light the auto-exposure follows (the sun behind a cloud): the exposure moves by
// `stops` over `ramp_s` seconds from `time_s`, a smooth step.
struct ExposureStep {
  double time_s = 0.0;
  double stops = 0.0;  // + brighter, - darker (EV)
  double ramp_s = 0.3;
};

struct CameraColorOptions {
  // Standard deviation of the red and blue gains' log against green (white balance error).
  double white_balance_error = 0.06;
  // Amplitude of the auto-exposure's slow drift through the record, stops (EV), and its period.
  double exposure_drift_stops = 0.2;
  double exposure_drift_period_s = 9.0;
  std::vector<ExposureStep> exposure_steps;
  // Sensor noise on 8-bit levels: variance read_noise_std^2 + shot_noise_gain * level.
  double read_noise_std = 1.0;    // levels
  double shot_noise_gain = 0.06;  // levels of variance per level of signal
  // Slight defocus: a Gaussian blur of this standard deviation, px (0: none).
  double defocus_sigma_px = 0.4;
  // JPEG quality of the MJPEG stream, 1-100 (0: no compression).
  int jpeg_quality = 85;
  // Chroma subsampling: 4:2:2 (halved horizontally; the Azure Kinect's MJPEG) or 4:2:0 (halved
  // both ways; OpenCV's JPEG default).
  bool chroma_422 = true;

  // Throws InputError naming the field.
  void Validate() const;
  // The defaults, with a darker step of -0.8 EV at `time_s` (--hard).
  static CameraColorOptions WithExposureStep(double time_s);
};

class CameraColor {
 public:
  // Draws the capture's white balance and drift phases from `seed`.
  CameraColor(const CameraColorOptions& options, uint64_t seed);

  // The auto-exposure's gain at `time_s` (1: the renderer's exposure).
  double ExposureGain(double time_s) const;
  // Red, green, blue gains of the white balance (green 1).
  const std::array<double, 3>& white_balance() const { return white_balance_; }

  // Replaces `image` (8-bit RGB) by what the camera delivers at `time_s`; `frame` seeds the
  // noise.
  void Apply(double time_s, int64_t frame, RgbImage& image) const;

 private:
  CameraColorOptions options_;
  uint64_t seed_ = 0;
  std::array<double, 3> white_balance_ = {1.0, 1.0, 1.0};
  double drift_phase_[2] = {0.0, 0.0};
};

// JPEG round trip of an 8-bit RGB image at `quality` (1-100), chroma 4:2:2 or 4:2:0.
RgbImage JpegRoundTrip(const RgbImage& image, int quality, bool chroma_422);

}  // namespace simtree::synth
