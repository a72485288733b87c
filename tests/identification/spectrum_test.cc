#include "simtree/identification/detail/spectrum.h"

#include <cmath>

#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/core/units.h"
#include "simtree/identification/detail/sampled_signal.h"

namespace simtree::identification {
namespace {

TEST(Spectrum, ASinusoidOnABinPeaksAtItsAmplitude) {
  std::vector<double> x(300);
  for (int i = 0; i < 300; ++i) x[i] = 0.7 * std::sin(kTwoPi * 1.5 * i / 30.0) + 2.0;
  const AmplitudeSpectrum s = ComputeAmplitudeSpectrum(x, 1.0 / 30);
  EXPECT_NEAR(s.bin_hz, 0.1, 1e-12);
  const int peak = static_cast<int>(std::max_element(s.amplitude.begin(), s.amplitude.end()) -
                                    s.amplitude.begin());
  EXPECT_EQ(peak, 15);
  EXPECT_NEAR(s.amplitude[15], 0.7, 1e-9);
  EXPECT_NEAR(s.amplitude[0], 0.0, 1e-9);  // the mean is removed
  SpectrumOptions padded;
  padded.zero_pad_factor = 16;
  const AmplitudeSpectrum p = ComputeAmplitudeSpectrum(x, 1.0 / 30, padded);
  EXPECT_GE(p.size(), 16 * 150);
  EXPECT_NEAR(*std::max_element(p.amplitude.begin(), p.amplitude.end()), 0.7, 1e-6);
}

TEST(Spectrum, TheExponentialWindowAddsItsDecayToTheHalfPowerBand) {
  // An undamped 2 Hz sinusoid windowed by e^(-rate t) has a Lorentzian of half width rate.
  std::vector<double> x(3000);
  for (int i = 0; i < 3000; ++i) x[i] = std::cos(kTwoPi * 2.0 * i / 100.0);
  SpectrumOptions o;
  o.window = SpectralWindow::kExponential;
  o.exponential_rate = 0.5;
  o.zero_pad_factor = 8;
  const AmplitudeSpectrum s = ComputeAmplitudeSpectrum(x, 0.01, o);
  const int peak = static_cast<int>(std::max_element(s.amplitude.begin(), s.amplitude.end()) -
                                    s.amplitude.begin());
  int right = peak;
  while (s.amplitude[right] > s.amplitude[peak] / std::sqrt(2.0)) ++right;
  EXPECT_NEAR(s.frequency(right) - s.frequency(peak), 0.5 / kTwoPi, 0.01);
}

TEST(SampledSignal, ResamplingMakesSkippedFramesGapsAndRefusesIrregularTimes) {
  Eigen::MatrixXd v(4, 1);
  v << 1, 2, 4, 5;
  const SampledSignal s = ResampleOnGrid({0.0, 0.1, 0.3, 0.4}, v, {true, true, true, true}, "x");
  EXPECT_EQ(s.size(), 5);
  EXPECT_FALSE(s.valid[2]);
  EXPECT_EQ(s.longest_gap(), 1);
  EXPECT_NEAR(s.FilledValues()(2, 0), 3.0, 1e-12);
  EXPECT_THROW(ResampleOnGrid({0.0, 0.1, 0.25, 0.4}, v, {true, true, true, true}, "x"), Error);
  SampledSignal ends = s;
  ends.valid[0] = false;
  ends.valid[4] = false;
  EXPECT_EQ(ends.TrimInvalidEnds().size(), 3);
  EXPECT_NEAR(ends.TrimInvalidEnds().start_time_s, 0.1, 1e-12);
}

TEST(SampledSignal, NoiseLevelIsTheWhiteNoiseNotTheSlowMotion) {
  SampledSignal s;
  s.dt = 1.0 / 30;
  s.values.resize(3000, 1);
  s.valid.assign(3000, true);
  uint64_t state = 12345;
  auto gauss = [&] {  // a deterministic Box-Muller from a tiny LCG
    auto u = [&] {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      return ((state >> 11) + 0.5) / 9007199254740992.0;
    };
    return std::sqrt(-2 * std::log(u())) * std::cos(kTwoPi * u());
  };
  for (int i = 0; i < 3000; ++i)
    s.values(i, 0) = 0.1 * std::sin(kTwoPi * i / 30.0) + 0.01 * gauss();
  EXPECT_NEAR(EstimateNoiseLevel(s)[0], 0.01, 0.0015);
}

}  // namespace
}  // namespace simtree::identification
