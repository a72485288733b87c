#pragma once
// Amplitude spectra of one channel of a record (FFT through OpenCV's cv::dft), with optional
// zero padding and a window.

#include <vector>

namespace simtree::identification {

enum class SpectralWindow {
  kNone,         // rectangular: the paper's plain FFT
  kHann,         // the usual leakage window (it widens a peak, so it biases damping up)
  kExponential,  // e^(-t/tau): adds a known decay rate 1/tau that is subtracted afterwards
};

const char* ToString(SpectralWindow window);

struct SpectrumOptions {
  SpectralWindow window = SpectralWindow::kNone;
  double exponential_rate = 0.0;  // decay rate the exponential window adds, 1/s
  int zero_pad_factor = 1;        // FFT length over the record length (1: no padding)
  bool remove_mean = true;        // subtract the record's mean before the FFT

  // Throws InputError naming the field for a value out of range.
  void Validate() const;
};

// Single-sided amplitude spectrum: bins 0 .. n/2 of an n-point FFT, bin k at k * bin_hz.
struct AmplitudeSpectrum {
  double bin_hz = 0.0;
  std::vector<double> amplitude;

  int size() const { return static_cast<int>(amplitude.size()); }
  double frequency(double bin) const { return bin * bin_hz; }
};

// `samples` must be finite (fill gaps first); `dt` the sample step in seconds.
AmplitudeSpectrum ComputeAmplitudeSpectrum(const std::vector<double>& samples, double dt,
                                           const SpectrumOptions& options = {});

}  // namespace simtree::identification
