#include "simtree/synth/detail/textures.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "simtree/synth/detail/sensor_random.h"

namespace simtree::synth {
namespace {

// A hash of a lattice point: two multiplies and shifts (textures need no more).
float LatticeValue(int64_t ix, int64_t iy, uint64_t seed) {
  uint64_t h = static_cast<uint64_t>(ix) * 0x9E3779B97F4A7C15ull ^
               static_cast<uint64_t>(iy) * 0xC2B2AE3D27D4EB4Full ^ seed;
  h ^= h >> 32;
  h *= 0xD6E8FEB86659FD93ull;
  h ^= h >> 32;
  return static_cast<float>(h >> 40) * (1.0f / 16777216.0f);
}

float Smooth(float t) { return t * t * (3.0f - 2.0f * t); }

// floor() without a library call (the x86-64 baseline has no rounding instruction).
int64_t FastFloor(double x) {
  const auto i = static_cast<int64_t>(x);
  return x < static_cast<double>(i) ? i - 1 : i;
}

Rgb Mix(const Rgb& a, const Rgb& b, float t) { return a + (b - a) * std::clamp(t, 0.0f, 1.0f); }

}  // namespace

float ValueNoise(double x, double y, uint64_t seed, int period_x) {
  int64_t x0 = FastFloor(x);
  int64_t x1 = x0 + 1;
  const int64_t y0 = FastFloor(y);
  const float tx = Smooth(static_cast<float>(x - static_cast<double>(x0)));
  const float ty = Smooth(static_cast<float>(y - static_cast<double>(y0)));
  if (period_x > 0) {
    x0 = ((x0 % period_x) + period_x) % period_x;
    x1 = ((x1 % period_x) + period_x) % period_x;
  }
  const float a = LatticeValue(x0, y0, seed);
  const float b = LatticeValue(x1, y0, seed);
  const float c = LatticeValue(x0, y0 + 1, seed);
  const float d = LatticeValue(x1, y0 + 1, seed);
  return (a + (b - a) * tx) + ((c + (d - c) * tx) - (a + (b - a) * tx)) * ty;
}

float FractalNoise(double x, double y, uint64_t seed, int octaves, int period_x) {
  float sum = 0.0f;
  float amplitude = 1.0f;
  float total = 0.0f;
  double scale = 1.0;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * ValueNoise(x * scale, y * scale, seed + o, period_x > 0 ? period_x << o : 0);
    total += amplitude;
    amplitude *= 0.5f;
    scale *= 2.0;
  }
  return sum / total;
}

Rgb BarkAlbedo(const BarkPoint& p, uint64_t seed) {
  // Streaks: lattice cells about 4 mm around the branch and 5 cm along it.
  const double circumference = 2.0 * std::numbers::pi * std::max(p.radius_m, 1e-4);
  const int cells_around = std::max(3, static_cast<int>(std::lround(circumference / 0.004)));
  const double x = p.angle_rad / (2.0 * std::numbers::pi) * cells_around;
  const double y = p.arc_length_m / 0.05;
  const uint64_t s = seed ^ MixBits(static_cast<uint64_t>(p.branch) + 17);
  const float streak = FractalNoise(x, y, s, 2, cells_around);
  const float blotch =
      ValueNoise(x * 0.15, p.arc_length_m / 0.3, s + 101, std::max(1, cells_around / 7));
  // Thick wood is grey and fissured, twigs (radius < 5 mm) browner and smooth.
  const float thickness = static_cast<float>(std::clamp((p.radius_m - 0.005) / 0.035, 0.0, 1.0));
  const Rgb twig(0.44f, 0.33f, 0.26f);
  const Rgb wood(0.43f, 0.40f, 0.36f);
  const Rgb fissure(0.20f, 0.17f, 0.15f);
  const Rgb lichen(0.47f, 0.52f, 0.40f);
  Rgb c = Mix(twig, wood, thickness);
  const float per_branch = 0.92f + 0.16f * LatticeValue(p.branch, 7, seed);
  c *= per_branch;
  const float fissure_amount = thickness * Smooth(std::clamp((0.48f - streak) * 4.0f, 0.0f, 1.0f));
  c = Mix(c, fissure, fissure_amount * 0.8f);
  c = Mix(c, lichen, thickness * std::clamp((blotch - 0.68f) * 4.0f, 0.0f, 0.6f));
  c *= 0.88f + 0.24f * streak;
  return c;
}

Rgb TapeAlbedo(double angle_rad, double offset_m, uint64_t seed) {
  const float wrinkle = ValueNoise(angle_rad * 6.0 / std::numbers::pi, offset_m / 0.008, seed, 12);
  return Rgb(0.80f, 0.07f, 0.09f) * (0.9f + 0.15f * wrinkle);
}

Rgb GroundAlbedo(double x, double y, uint64_t seed) {
  const float patches = ValueNoise(x / 1.5, y / 1.5, seed + 11);
  const float straw = ValueNoise(x / 0.4, y / 0.4, seed + 23);
  const float blades = ValueNoise(x / 0.012, y / 0.012, seed + 37);
  const Rgb grass(0.30f, 0.36f, 0.18f);
  const Rgb dry(0.50f, 0.46f, 0.30f);
  const Rgb soil(0.36f, 0.29f, 0.22f);
  Rgb c = Mix(grass, dry, (straw - 0.35f) * 2.0f);
  c = Mix(c, soil, (patches - 0.62f) * 5.0f);
  return c * (0.85f + 0.3f * blades);
}

Rgb HedgeAlbedo(double along_m, double z, uint64_t seed) {
  const float clumps = ValueNoise(along_m / 0.35, z / 0.35, seed + 41);
  const float leaves = ValueNoise(along_m / 0.03, z / 0.03, seed + 43);
  const Rgb dark(0.07f, 0.14f, 0.06f);
  const Rgb light(0.20f, 0.30f, 0.13f);
  return Mix(dark, light, clumps * 0.8f + leaves * 0.4f - 0.1f);
}

Rgb RopeAlbedo(double along_m) {
  const float twist = 0.5f + 0.5f * static_cast<float>(std::sin(along_m / 0.004));
  return Rgb(0.82f, 0.72f, 0.48f) * (0.85f + 0.15f * twist);
}

Rgb ShrubAlbedo(double along_m, uint64_t seed) {
  const float n = ValueNoise(along_m / 0.05, 0.5, seed + 59);
  return Rgb(0.36f, 0.31f, 0.27f) * (0.85f + 0.3f * n);
}

Rgb SkyColor(const Eigen::Vector3d& direction_world) {
  const double n = direction_world.norm();
  const double elevation = n > 0 ? std::clamp(direction_world.z() / n, 0.0, 1.0) : 0.0;
  const float t = static_cast<float>(std::sqrt(elevation));
  return Mix(Rgb(0.83f, 0.86f, 0.90f), Rgb(0.40f, 0.56f, 0.80f), t);
}

}  // namespace simtree::synth
