#pragma once
// A uniformly sampled, possibly gappy, multi-channel signal: what the estimators read. A
// deflection signal has two channels (the two bending planes of a marker link); a sample is
// invalid when a marker it depends on was lost in that frame (or the frame was dropped).

#include <string>
#include <vector>

#include <Eigen/Core>

namespace simtree::identification {

struct SampledSignal {
  double start_time_s = 0.0;  // time of sample 0 (the record's clock)
  double dt = 0.0;            // seconds between samples
  Eigen::MatrixXd values;     // samples x channels; NaN where the sample is not valid
  std::vector<bool> valid;    // per sample
  std::vector<std::string> channel_names;

  int size() const { return static_cast<int>(values.rows()); }
  int channels() const { return static_cast<int>(values.cols()); }
  // Record length N dt (the span the FFT resolves: 1 / duration is its bin width).
  double duration_s() const { return size() * dt; }
  double time_at(int sample) const { return start_time_s + sample * dt; }
  int valid_count() const;
  // The longest run of invalid samples.
  int longest_gap() const;

  // Samples [begin, end) as a new signal.
  SampledSignal Slice(int begin, int end) const;
  // Drops invalid samples at both ends.
  SampledSignal TrimInvalidEnds() const;
  // Linear interpolation across gaps (ends must be valid: TrimInvalidEnds first), for the methods
  // that need every sample (FFT, matrix pencil). Returns the filled values.
  Eigen::MatrixXd FilledValues() const;
};

// Builds a signal on the uniform grid t0 + k dt from samples at `times` (increasing). The step is
// the median spacing; a time that falls between grid points by more than a quarter step is an
// InputError (the record is not uniformly sampled), a skipped grid point becomes a gap.
SampledSignal ResampleOnGrid(const std::vector<double>& times, const Eigen::MatrixXd& values,
                             const std::vector<bool>& valid, const std::string& source);

// Robust noise level of each channel: the median absolute second difference of valid
// consecutive samples, scaled to a standard deviation for white noise (MAD / 0.6745 / sqrt(6)).
// Oscillations well below the Nyquist rate barely reach the second differences, so this measures
// the measurement noise rather than the motion.
Eigen::VectorXd EstimateNoiseLevel(const SampledSignal& signal);

}  // namespace simtree::identification
