#pragma once
// Natural frequency and damping ratio of the dominant mode of a free-decay record (paper III-C).
//
// Three estimators, all runnable on the same signal (docs/identification.md compares them):
//  (a) kHalfPowerFft: the paper's. Plain FFT of the record, the peak bin is f0, and
//      zeta = (f_r - f_l) / (2 f0) where the amplitude falls to peak / sqrt(2) (paper Eq. 2; the
//      crossings linearly interpolated between bins). On a 10 s record the bins are 0.1 Hz apart,
//      wider than the whole half-power band of a lightly damped branch, so zeta comes out too
//      large (NOTES.md).
//  (b) kInterpolatedSpectrum: the same half-power reading on a zero-padded spectrum with an
//      exponential window. The window makes the record decay to ~e^-4 by its end, so truncation no
//      longer widens the peak; its known decay rate is subtracted from the measured bandwidth
//      afterwards (the standard exponential-window correction of impact testing). The peak is
//      refined by a parabola through the three highest padded bins.
//  (c) kDampedSinusoidFit: a time-domain model of the whole record, a constant plus K damped
//      sinusoids sharing their poles across channels, started from the matrix pencil (Hua &
//      Sarkar 1990) and refined by Levenberg-Marquardt on the valid samples only (gaps need no
//      filling); K chosen by BIC. Standard errors come from the Jacobian, inflated for correlated
//      residuals. It has no frequency-resolution limit; this is the default (measured best).
//
// No estimator invents a value: when the record cannot support one (flat, too short, too gappy,
// no peak, no half-power band) the estimate says so in `status` and `message` and leaves NaN.

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "simtree/identification/detail/sampled_signal.h"
#include "simtree/identification/detail/spectrum.h"

namespace simtree::identification {

enum class EstimatorKind { kHalfPowerFft, kInterpolatedSpectrum, kDampedSinusoidFit };

// The estimator used when none is named (the one that measures best; docs/identification.md).
inline constexpr EstimatorKind kDefaultEstimator = EstimatorKind::kDampedSinusoidFit;

// "half_power_fft", "interpolated_spectrum", "damped_sinusoid_fit".
const char* ToString(EstimatorKind kind);
std::optional<EstimatorKind> ParseEstimatorKind(std::string_view name);
std::vector<EstimatorKind> AllEstimators();

enum class EstimateStatus {
  kOk,
  kTooFewSamples,  // fewer valid samples than any estimate needs
  kTooManyGaps,    // too large a share of the record is missing
  kFlat,           // no motion above the measurement noise
  kNoPeak,         // nothing oscillates inside the frequency band
  kTooShort,       // the record holds fewer than `min_periods` periods of the mode
  kNoDamping,      // frequency found, damping could not be (no half-power band, ...)
  kFailed,         // the fit did not converge to a decaying mode
  kMissingMarker,  // (set by identify) the link's markers have no trajectory
};
// "ok", "too_few_samples", "too_many_gaps", "flat", "no_peak", "too_short", "no_damping",
// "failed", "missing_marker".
const char* ToString(EstimateStatus status);

// One estimated mode. Values that could not be estimated are NaN; so are standard deviations an
// estimator does not give (the spectral ones).
struct ModalEstimate {
  EstimateStatus status = EstimateStatus::kOk;
  std::string message;  // why a value is missing, or notes ("3 gaps filled")
  double frequency_hz = kNaN;
  double damping_ratio = kNaN;
  double frequency_std_hz = kNaN;
  double damping_std = kNaN;
  double amplitude = kNaN;  // of the mode at the start of the record, signal units
  int channel = -1;         // the channel (bending plane) that carried it

  bool has_frequency() const { return std::isfinite(frequency_hz); }
  bool has_damping() const { return std::isfinite(damping_ratio); }

  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
};

struct EstimatorOptions {
  // Band searched for the mode (Hz); 0: from the record, one period over the record at the low
  // end, 0.8 of the Nyquist frequency at the high end.
  double min_frequency_hz = 0.0;
  double max_frequency_hz = 0.0;
  double min_periods = 2.0;       // periods of a mode the record must hold, else kTooShort
  double max_gap_fraction = 0.5;  // share of invalid samples above which kTooManyGaps
  // kFlat unless the signal's standard deviation exceeds this multiple of its noise level
  // (EstimateNoiseLevel).
  double flat_ratio = 1.2;

  // (b) interpolated spectrum.
  int zero_pad_factor = 16;                              // FFT length over the record length, >= 1
  SpectralWindow window = SpectralWindow::kExponential;  // applied before the padded FFT
  double window_decay_nepers = 4.0;  // the exponential window's decay over the record, Np

  // (c) damped sinusoid fit.
  int max_modes = 6;               // most modes the model may hold (chosen by BIC)
  double max_damping_ratio = 0.5;  // poles damped more than this are noise, not modes
  int max_iterations = 200;        // Levenberg-Marquardt iterations per fit

  // Throws InputError naming the field for a value out of range.
  void Validate() const;
};

// A peak read off a spectrum by (a) or (b), for reports and plots.
struct SpectralPeak {
  int channel = -1;
  double peak_hz = 0.0, left_hz = 0.0, right_hz = 0.0;  // band edges NaN when not found
  double peak_amplitude = 0.0;
  double window_rate = 0.0;  // 1/s added by the exponential window
  AmplitudeSpectrum spectrum;
};

// One mode of the time-domain model y_c(t) = d_c + sum_k e^(-s_k t) (a_ck cos w_k t + b_ck sin w_k
// t) with t from the start of the record.
struct FittedMode {
  double decay_rate = 0.0;                       // s_k, 1/s
  double angular_frequency = 0.0;                // w_k (damped), rad/s
  Eigen::VectorXd cos_amplitude, sin_amplitude;  // per channel
  double frequency_hz = 0.0;                     // undamped natural frequency sqrt(w^2 + s^2)/2pi
  double damping_ratio = 0.0;                    // s / sqrt(w^2 + s^2)
  double frequency_std_hz = 0.0, damping_std = 0.0;
  // Amplitude at t = 0 over all channels, and in each channel.
  double amplitude = 0.0;
  Eigen::VectorXd channel_amplitude;
  // Far larger than anything the record shows (MarkModesBeyondRecord): kept in the model, never
  // reported.
  bool beyond_record = false;
};

struct DampedSinusoidFit {
  bool converged = false;
  std::string message;
  std::vector<FittedMode> modes;  // strongest first
  Eigen::VectorXd offsets;        // d_c
  double rms_residual = 0.0;
  double residual_correlation = 0.0;  // lag-1 autocorrelation of the residuals
  int iterations = 0;
  int candidates = 0;  // poles the matrix pencil offered inside the band

  // The model at every sample of `signal` (samples x channels), for plots and residuals.
  Eigen::MatrixXd Evaluate(const SampledSignal& signal) const;
};

// The result of one estimator on one signal: the dominant mode over all channels, each channel's
// own dominant mode (a bending plane's value) and what the estimator saw.
struct SignalEstimate {
  EstimatorKind estimator = kDefaultEstimator;
  ModalEstimate dominant;
  std::vector<ModalEstimate> per_channel;
  std::vector<SpectralPeak> peaks;       // (a), (b): one per channel
  std::optional<DampedSinusoidFit> fit;  // (c)
  double noise_level = 0.0;              // largest channel noise (EstimateNoiseLevel)
  double duration_s = 0.0;               // record length used, s
  bool joint_poles = false;  // (c) read on poles fitted to every link at once (joint_poles.h)
};

SignalEstimate EstimateModes(const SampledSignal& signal, EstimatorKind estimator,
                             const EstimatorOptions& options = {});

// The band EstimateModes searches on a record `duration_s` long sampled every `dt` s:
// options' band, or from one period over the record to 0.8 of the Nyquist frequency.
struct SearchBand {
  double min_hz = 0.0, max_hz = 0.0;
};
SearchBand BandOf(const EstimatorOptions& options, double duration_s, double dt);

// Sets a fitted mode's pole (decay rate s, damped angular frequency w >= 0), its natural
// frequency and damping ratio, and their standard deviations from the 2 x 2 covariance of (s, w)
// (infinite where the covariance cannot say: an unresolved direction, NaN).
void SetPole(double decay_rate, double angular_frequency, const Eigen::Matrix2d& covariance,
             FittedMode& mode);

// The estimators on their own (no flatness or gap checks; `signal` trimmed of invalid ends).
// `min_hz` / `max_hz` is the band searched.
SpectralPeak FindHalfPowerPeak(const SampledSignal& signal, int channel,
                               const SpectrumOptions& spectrum, bool interpolate, double min_hz,
                               double max_hz);
DampedSinusoidFit FitDampedSinusoids(const SampledSignal& signal, double min_hz, double max_hz,
                                     const EstimatorOptions& options = {});

// Estimator (c)'s reading of a fitted model of a `channels`-channel record `record_s` long: the
// dominant mode is the strongest inside [min_hz, max_hz] (amplitude times the integral of its
// envelope over the record, a (1 - e^(-s T)) / s), each channel's the strongest in that channel.
// Sets out.dominant, out.per_channel and out.fit.
void ReadFittedModes(DampedSinusoidFit fit, int channels, double record_s, double min_hz,
                     double max_hz, const EstimatorOptions& options, SignalEstimate& out);

// Marks the modes of `fit` whose amplitude at the record's start is more than
// `kMaxAmplitudePerExcursion` times the record's largest excursion from the fitted rest (offsets):
// a free decay does not hold a component that much larger than the motion itself. Such a mode is
// a fit artefact (large poles cancelling across a long gap, or a trend): on a link ringing at
// 1.46 Hz whose tape was lost for 25 frames, one read 0.68 Hz, zeta 0.46, with a 7% sd.
inline constexpr double kMaxAmplitudePerExcursion = 4.0;
void MarkModesBeyondRecord(const SampledSignal& signal, DampedSinusoidFit& fit);

}  // namespace simtree::identification
