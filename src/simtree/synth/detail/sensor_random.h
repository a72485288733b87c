#pragma once
// Counter-based random numbers for the virtual sensor: the numbers drawn for one pixel are a pure
// function of (seed, frame, pixel, stream), so a render gives the same bytes whatever the thread
// count or the order in which pixels are visited. (A std::mt19937_64 per pixel would cost more to
// seed than the pixel costs to render; a shared one would make the result depend on scheduling.)

#include <cmath>
#include <cstdint>
#include <numbers>

namespace simtree::synth {

// The SplitMix64 finaliser: a bijective 64-bit mix with good avalanche.
inline uint64_t MixBits(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// What a random stream is used for; streams of one pixel never share numbers.
enum class RandomStream : uint64_t {
  kDepth = 1,
  kColor = 2,
  kOutlier = 3,
  kScene = 4,
  kClick = 5,   // pull/init.json's simulated clicks (init_clicks.h)
  kCamera = 6,  // the camera's colour pipeline (camera_color.h)
};

class PixelRandom {
 public:
  PixelRandom(uint64_t seed, uint64_t frame, uint64_t pixel, RandomStream stream)
      : state_(MixBits(MixBits(MixBits(seed) ^ frame) ^
                       ((pixel << 3) | static_cast<uint64_t>(stream)))) {}

  uint64_t NextBits() {
    state_ += 0x9E3779B97F4A7C15ull;
    return MixBits(state_);
  }
  // Uniform in [0, 1) with 53 random bits.
  double Uniform() { return static_cast<double>(NextBits() >> 11) * 0x1.0p-53; }
  // Standard normal (Box-Muller; the first uniform is kept away from 0).
  double Normal() {
    const double u1 = Uniform();
    return NormalFromUniforms(u1, Uniform());
  }
  // A cheap, nearly normal number with mean 0 and variance 1, bounded by +-2 sqrt(3): the sum of
  // four 16-bit uniforms (Irwin-Hall). For colour noise, where the tails do not matter.
  double RoughNormal() {
    const uint64_t bits = NextBits();
    const double sum = static_cast<double>((bits & 0xFFFF) + ((bits >> 16) & 0xFFFF) +
                                           ((bits >> 32) & 0xFFFF) + (bits >> 48)) *
                       (1.0 / 65536.0);
    return (sum - 2.0) * 1.7320508075688772;
  }
  // Box-Muller of two uniforms in [0, 1).
  static double NormalFromUniforms(double u1, double u2) {
    return std::sqrt(-2.0 * std::log(1.0 - u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  uint64_t state_;
};

}  // namespace simtree::synth
