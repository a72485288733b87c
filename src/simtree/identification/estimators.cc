#include "simtree/identification/estimators.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "simtree/core/option_checks.h"
#include "simtree/core/units.h"

namespace simtree::identification {
namespace {

ModalEstimate Failed(EstimateStatus status, std::string message) {
  ModalEstimate e;
  e.status = status;
  e.message = std::move(message);
  return e;
}

// Where the spectrum falls to `level` walking from `peak` by `step` (-1 left, +1 right), linearly
// interpolated between bins; NaN when it does not before the end of the spectrum.
double Crossing(const AmplitudeSpectrum& s, int peak, int step, double level) {
  for (int i = peak; i + step >= 1 && i + step < s.size(); i += step) {
    const double a = s.amplitude[i], b = s.amplitude[i + step];
    if (b <= level) {
      const double fraction = (a - level) / (a - b);
      return s.frequency(i + step * fraction);
    }
  }
  return kNaN;
}

// A mode with fewer than `min_periods` periods in the record cannot be told from a trend.
// (Inclusive: a plain FFT's bin k is exactly k periods, so a peak in bin 2 may be a slower mode.)
bool TooShort(double frequency_hz, double duration_s, const EstimatorOptions& options) {
  return frequency_hz * duration_s <= options.min_periods;
}

std::string TooShortMessage(double frequency_hz, double duration_s,
                            const EstimatorOptions& options) {
  return fmt::format(
      "the record ({:.2f} s) holds fewer than {:g} periods of the strongest "
      "oscillation (near {:.2f} Hz)",
      duration_s, options.min_periods, frequency_hz);
}

// (a) and (b): each channel's half-power reading; the dominant is the channel with the highest
// peak.
void EstimateSpectral(const SampledSignal& signal, EstimatorKind kind, double min_hz, double max_hz,
                      const EstimatorOptions& options, SignalEstimate& out) {
  SpectrumOptions spectrum;
  const bool interpolate = kind == EstimatorKind::kInterpolatedSpectrum;
  if (interpolate) {
    spectrum.zero_pad_factor = options.zero_pad_factor;
    spectrum.window = options.window;
    spectrum.exponential_rate = options.window_decay_nepers / signal.duration_s();
  }
  double best_amplitude = -1;
  for (int c = 0; c < signal.channels(); ++c) {
    SpectralPeak peak = FindHalfPowerPeak(signal, c, spectrum, interpolate, min_hz, max_hz);
    ModalEstimate e;
    e.channel = c;
    if (!(peak.peak_amplitude > 0)) {
      e = Failed(EstimateStatus::kNoPeak,
                 fmt::format("no spectral peak between {:.2f} and {:.2f} Hz", min_hz, max_hz));
      e.channel = c;
    } else {
      const double added = peak.window_rate / (kTwoPi * peak.peak_hz);
      double zeta = (peak.right_hz - peak.left_hz) / (2 * peak.peak_hz) - added;
      e.amplitude = peak.peak_amplitude;
      e.frequency_hz = peak.peak_hz;
      if (interpolate && std::isfinite(zeta) && zeta > 0) {
        // The peak of a damped mode sits at the damped frequency; report the natural one.
        e.frequency_hz = peak.peak_hz / std::sqrt(std::max(1e-6, 1 - zeta * zeta));
      }
      if (TooShort(e.frequency_hz, signal.duration_s(), options)) {
        e = Failed(EstimateStatus::kTooShort,
                   TooShortMessage(peak.peak_hz, signal.duration_s(), options));
        e.channel = c;
      } else if (!std::isfinite(zeta)) {
        e.status = EstimateStatus::kNoDamping;
        e.message = "the spectrum does not fall to half power on both sides of the peak";
      } else if (zeta <= 0) {
        e.status = EstimateStatus::kNoDamping;
        e.message = fmt::format(
            "the half-power band ({:.4f} Hz) is narrower than the window's own "
            "decay accounts for",
            peak.right_hz - peak.left_hz);
      } else {
        e.damping_ratio = zeta;
      }
    }
    out.per_channel.push_back(e);
    if (peak.peak_amplitude > best_amplitude &&
        out.per_channel.back().status != EstimateStatus::kNoPeak) {
      best_amplitude = peak.peak_amplitude;
      out.dominant = out.per_channel.back();
    }
    out.peaks.push_back(std::move(peak));
  }
  if (best_amplitude < 0) out.dominant = out.per_channel.front();
}

// (c): one joint fit; the dominant mode is the strongest inside the band, each channel's the
// strongest in that channel. "Strongest" is what the paper's dominant frequency means: the highest
// peak of the record's spectrum, which for a decaying mode is its amplitude times the integral of
// its envelope over the record, a (1 - e^(-s T)) / s. A stiff twig's mode may start larger than the
// tree's sway and still die out within a second; the sway then owns the spectrum.
void EstimateFit(const SampledSignal& signal, double min_hz, double max_hz,
                 const EstimatorOptions& options, SignalEstimate& out) {
  DampedSinusoidFit fit = FitDampedSinusoids(signal, min_hz, max_hz, options);
  MarkModesBeyondRecord(signal, fit);
  ReadFittedModes(std::move(fit), signal.channels(), signal.duration_s(), min_hz, max_hz, options,
                  out);
}

}  // namespace

void ReadFittedModes(DampedSinusoidFit fit, int channels, double record_s, double min_hz,
                     double max_hz, const EstimatorOptions& options, SignalEstimate& out) {
  auto from_mode = [&](const FittedMode& mode, int channel) {
    ModalEstimate e;
    e.channel = channel;
    e.amplitude = channel < 0 ? mode.amplitude : mode.channel_amplitude[channel];
    if (TooShort(mode.frequency_hz, record_s, options)) {
      e = Failed(EstimateStatus::kTooShort, TooShortMessage(mode.frequency_hz, record_s, options));
      e.channel = channel;
      return e;
    }
    if (mode.damping_ratio <= 0) {
      e = Failed(EstimateStatus::kFailed,
                 fmt::format("the strongest mode ({:.3f} Hz) does not decay (zeta {:.4f})",
                             mode.frequency_hz, mode.damping_ratio));
      e.channel = channel;
      return e;
    }
    e.frequency_hz = mode.frequency_hz;
    e.damping_ratio = mode.damping_ratio;
    e.frequency_std_hz = mode.frequency_std_hz;
    e.damping_std = mode.damping_std;
    if (!fit.converged) e.message = fit.message;
    return e;
  };
  // A pole the refinement pushed past `max_damping_ratio` models a drift or a burst of noise, not
  // a mode: it is kept in the model but never reported.
  auto in_band = [&](const FittedMode& m) {
    return m.frequency_hz >= min_hz && m.frequency_hz <= max_hz &&
           m.damping_ratio <= options.max_damping_ratio && !m.beyond_record;
  };
  auto peak = [&](const FittedMode& m, int channel) {
    const double a = channel < 0 ? m.amplitude : m.channel_amplitude[channel];
    const double s = m.decay_rate;
    return a * (s * record_s > 1e-9 ? (1.0 - std::exp(-s * record_s)) / s : record_s);
  };
  // The strongest mode with enough periods in the record; only when there is none, the strongest
  // slower one (reported as too short). A slow drift the model absorbed into a pole is not the
  // swing the record holds several periods of.
  auto strongest = [&](int channel) -> const FittedMode* {
    const FittedMode* best = nullptr;
    for (bool long_enough : {true, false}) {
      for (const FittedMode& m : fit.modes) {
        if (!in_band(m) || TooShort(m.frequency_hz, record_s, options) == long_enough) continue;
        if (!best || peak(m, channel) > peak(*best, channel)) best = &m;
      }
      if (best) break;
    }
    return best;
  };
  const FittedMode* dominant = strongest(-1);
  if (!dominant) {
    out.dominant =
        Failed(EstimateStatus::kNoPeak,
               !fit.message.empty()
                   ? fit.message
                   : fmt::format("no mode between {:.2f} and {:.2f} Hz damped less than zeta {:g}",
                                 min_hz, max_hz, options.max_damping_ratio));
  } else {
    out.dominant = from_mode(*dominant, -1);
    int channel = 0;
    for (int c = 1; c < channels; ++c) {
      if (dominant->channel_amplitude[c] > dominant->channel_amplitude[channel]) channel = c;
    }
    out.dominant.channel = channel;
  }
  for (int c = 0; c < channels; ++c) {
    const FittedMode* mode = strongest(c);
    out.per_channel.push_back(mode ? from_mode(*mode, c)
                                   : Failed(EstimateStatus::kNoPeak, out.dominant.message));
    out.per_channel.back().channel = c;
  }
  out.fit = std::move(fit);
}

void MarkModesBeyondRecord(const SampledSignal& signal, DampedSinusoidFit& fit) {
  if (fit.offsets.size() != signal.channels()) return;  // no model
  double excursion = 0.0;
  for (int i = 0; i < signal.size(); ++i) {
    if (!signal.valid[i]) continue;
    excursion = std::max(excursion, (signal.values.row(i).transpose() - fit.offsets).norm());
  }
  for (FittedMode& mode : fit.modes) {
    mode.beyond_record = mode.amplitude > kMaxAmplitudePerExcursion * excursion;
  }
}

void EstimatorOptions::Validate() const {
  CheckNonNegative("min_frequency_hz", min_frequency_hz);
  CheckNonNegative("max_frequency_hz", max_frequency_hz);
  if (min_frequency_hz > 0 && max_frequency_hz > 0) {
    CheckThat(max_frequency_hz > min_frequency_hz, "max_frequency_hz",
              fmt::format("> min_frequency_hz ({})", min_frequency_hz), max_frequency_hz);
  }
  CheckPositive("min_periods", min_periods);
  CheckShare("max_gap_fraction", max_gap_fraction);
  CheckNonNegative("flat_ratio", flat_ratio);
  CheckAtLeast("zero_pad_factor", zero_pad_factor, 1);
  CheckNonNegative("window_decay_nepers", window_decay_nepers);
  CheckAtLeast("max_modes", max_modes, 1);
  CheckThat(max_damping_ratio > 0 && max_damping_ratio < 1, "max_damping_ratio",
            "a damping ratio in (0, 1)", max_damping_ratio);
  CheckAtLeast("max_iterations", max_iterations, 1);
}

SearchBand BandOf(const EstimatorOptions& options, double duration_s, double dt) {
  const double nyquist = 0.5 / dt;
  return {
      options.min_frequency_hz > 0 ? options.min_frequency_hz : 1.0 / duration_s,
      options.max_frequency_hz > 0 ? std::min(options.max_frequency_hz, nyquist) : 0.8 * nyquist};
}

const char* ToString(EstimatorKind kind) {
  switch (kind) {
    case EstimatorKind::kHalfPowerFft:
      return "half_power_fft";
    case EstimatorKind::kInterpolatedSpectrum:
      return "interpolated_spectrum";
    case EstimatorKind::kDampedSinusoidFit:
      return "damped_sinusoid_fit";
  }
  return "?";
}

std::optional<EstimatorKind> ParseEstimatorKind(std::string_view name) {
  for (EstimatorKind kind : AllEstimators()) {
    if (name == ToString(kind)) return kind;
  }
  return std::nullopt;
}

std::vector<EstimatorKind> AllEstimators() {
  return {EstimatorKind::kHalfPowerFft, EstimatorKind::kInterpolatedSpectrum,
          EstimatorKind::kDampedSinusoidFit};
}

const char* ToString(EstimateStatus status) {
  switch (status) {
    case EstimateStatus::kOk:
      return "ok";
    case EstimateStatus::kTooFewSamples:
      return "too_few_samples";
    case EstimateStatus::kTooManyGaps:
      return "too_many_gaps";
    case EstimateStatus::kFlat:
      return "flat";
    case EstimateStatus::kNoPeak:
      return "no_peak";
    case EstimateStatus::kTooShort:
      return "too_short";
    case EstimateStatus::kNoDamping:
      return "no_damping";
    case EstimateStatus::kFailed:
      return "failed";
    case EstimateStatus::kMissingMarker:
      return "missing_marker";
  }
  return "?";
}

SpectralPeak FindHalfPowerPeak(const SampledSignal& signal, int channel,
                               const SpectrumOptions& options, bool interpolate, double min_hz,
                               double max_hz) {
  SpectralPeak out;
  out.channel = channel;
  const Eigen::MatrixXd filled = signal.FilledValues();
  const std::vector<double> samples(filled.col(channel).data(),
                                    filled.col(channel).data() + filled.rows());
  out.spectrum = ComputeAmplitudeSpectrum(samples, signal.dt, options);
  out.window_rate = options.window == SpectralWindow::kExponential ? options.exponential_rate : 0;
  const AmplitudeSpectrum& s = out.spectrum;
  if (s.size() < 3) return out;
  const int first = std::max(1, static_cast<int>(std::ceil(min_hz / s.bin_hz)));
  const int last = std::min(s.size() - 2, static_cast<int>(std::floor(max_hz / s.bin_hz)));
  int peak = -1;
  for (int k = first; k <= last; ++k) {
    // A peak is a local maximum; the low end of the band often just continues the mean's leakage.
    if (s.amplitude[k] < s.amplitude[k - 1] || s.amplitude[k] < s.amplitude[k + 1]) continue;
    if (peak < 0 || s.amplitude[k] > s.amplitude[peak]) peak = k;
  }
  if (peak < 0 || s.amplitude[peak] <= 0) return out;
  double bin = peak, amplitude = s.amplitude[peak];
  if (interpolate) {
    const double a = s.amplitude[peak - 1], b = s.amplitude[peak], c = s.amplitude[peak + 1];
    const double denominator = a - 2 * b + c;
    if (denominator < 0) {
      const double delta = std::clamp(0.5 * (a - c) / denominator, -0.5, 0.5);
      bin = peak + delta;
      amplitude = b - 0.25 * (a - c) * delta;
    }
  }
  out.peak_hz = s.frequency(bin);
  out.peak_amplitude = amplitude;
  const double level = amplitude / std::sqrt(2.0);
  out.left_hz = Crossing(s, peak, -1, level);
  out.right_hz = Crossing(s, peak, +1, level);
  return out;
}

SignalEstimate EstimateModes(const SampledSignal& input, EstimatorKind estimator,
                             const EstimatorOptions& options) {
  options.Validate();
  SignalEstimate out;
  out.estimator = estimator;
  auto fail_all = [&](EstimateStatus status, const std::string& message) {
    out.dominant = Failed(status, message);
    out.per_channel.assign(std::max(1, input.channels()), out.dominant);
    return out;
  };
  const SampledSignal signal = input.TrimInvalidEnds();
  out.duration_s = signal.duration_s();
  constexpr int kMinSamples = 16;
  if (signal.valid_count() < kMinSamples || signal.channels() == 0) {
    return fail_all(EstimateStatus::kTooFewSamples,
                    fmt::format("{} valid samples; an estimate needs at least {}",
                                signal.valid_count(), kMinSamples));
  }
  const double missing = 1.0 - double(signal.valid_count()) / signal.size();
  if (missing > options.max_gap_fraction) {
    return fail_all(EstimateStatus::kTooManyGaps,
                    fmt::format("{:.0f}% of the record is missing (more than {:.0f}%)",
                                100 * missing, 100 * options.max_gap_fraction));
  }
  const Eigen::VectorXd noise = EstimateNoiseLevel(signal);
  out.noise_level = noise.maxCoeff();
  bool moving = false;
  double largest_spread = 0;
  for (int c = 0; c < signal.channels(); ++c) {
    // Two passes: a constant record must give exactly zero, not a rounding residue.
    double sum = 0;
    int count = 0;
    for (int i = 0; i < signal.size(); ++i) {
      if (!signal.valid[i]) continue;
      sum += signal.values(i, c);
      ++count;
    }
    const double mean = sum / count;
    double sum2 = 0;
    for (int i = 0; i < signal.size(); ++i) {
      if (signal.valid[i]) sum2 += (signal.values(i, c) - mean) * (signal.values(i, c) - mean);
    }
    const double spread = std::sqrt(sum2 / count);
    largest_spread = std::max(largest_spread, spread);
    if (spread > options.flat_ratio * noise[c] && spread > 1e-12 * (1 + std::abs(mean))) {
      moving = true;
    }
  }
  if (!moving) {
    return fail_all(EstimateStatus::kFlat,
                    fmt::format("no motion above the noise (standard deviation {:.3g}, noise "
                                "{:.3g})",
                                largest_spread, out.noise_level));
  }
  const auto [min_hz, max_hz] = BandOf(options, signal.duration_s(), signal.dt);
  if (estimator == EstimatorKind::kDampedSinusoidFit) {
    EstimateFit(signal, min_hz, max_hz, options, out);
  } else {
    EstimateSpectral(signal, estimator, min_hz, max_hz, options, out);
  }
  const int gaps = signal.size() - signal.valid_count();
  if (gaps > 0 && out.dominant.status == EstimateStatus::kOk) {
    const std::string note =
        fmt::format("{} missing samples (longest gap {})", gaps, signal.longest_gap());
    out.dominant.message = out.dominant.message.empty() ? note : out.dominant.message + "; " + note;
  }
  return out;
}

}  // namespace simtree::identification
