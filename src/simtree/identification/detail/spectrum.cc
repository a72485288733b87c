#include "simtree/identification/detail/spectrum.h"

#include <cmath>
#include <numeric>

#include <opencv2/core.hpp>

#include "simtree/core/option_checks.h"
#include "simtree/core/units.h"

namespace simtree::identification {

const char* ToString(SpectralWindow window) {
  switch (window) {
    case SpectralWindow::kNone:
      return "none";
    case SpectralWindow::kHann:
      return "hann";
    case SpectralWindow::kExponential:
      return "exponential";
  }
  return "?";
}

void SpectrumOptions::Validate() const {
  CheckNonNegative("exponential_rate", exponential_rate);
  CheckAtLeast("zero_pad_factor", zero_pad_factor, 1);
}

AmplitudeSpectrum ComputeAmplitudeSpectrum(const std::vector<double>& samples, double dt,
                                           const SpectrumOptions& options) {
  options.Validate();
  AmplitudeSpectrum out;
  const int n = static_cast<int>(samples.size());
  if (n < 2 || !(dt > 0)) return out;
  const double mean =
      options.remove_mean ? std::accumulate(samples.begin(), samples.end(), 0.0) / n : 0.0;
  const int length = cv::getOptimalDFTSize(options.zero_pad_factor * n);
  cv::Mat input = cv::Mat::zeros(1, length, CV_64F);
  auto* x = input.ptr<double>();
  for (int i = 0; i < n; ++i) {
    double w = 1.0;
    switch (options.window) {
      case SpectralWindow::kNone:
        break;
      case SpectralWindow::kHann:
        w = 0.5 - 0.5 * std::cos(kTwoPi * i / (n - 1));
        break;
      case SpectralWindow::kExponential:
        w = std::exp(-options.exponential_rate * i * dt);
        break;
    }
    x[i] = (samples[i] - mean) * w;
  }
  cv::Mat output;
  cv::dft(input, output, cv::DFT_COMPLEX_OUTPUT);
  const auto* z = output.ptr<cv::Vec2d>();
  out.bin_hz = 1.0 / (length * dt);
  out.amplitude.resize(length / 2 + 1);
  for (int k = 0; k <= length / 2; ++k) {
    // Scaled so a sinusoid of amplitude A spanning the whole unpadded record peaks near A.
    out.amplitude[k] = std::hypot(z[k][0], z[k][1]) * 2.0 / n;
  }
  return out;
}

}  // namespace simtree::identification
