#pragma once
// Procedural colours of the virtual capture scene: bark with streaks along the branch, red tape,
// winter grass and soil, an evergreen hedge, a rope, a sky gradient. Albedos are display values
// in [0, 1] per channel; the renderer shades them with a sun and an ambient term.
// All patterns are deterministic functions of position and a seed.

#include <cstdint>

#include <Eigen/Core>

namespace simtree::synth {

using Rgb = Eigen::Vector3f;

// Smooth value noise in [0, 1] on a unit lattice; `period_x` > 0 makes it periodic in x (so a
// pattern wrapped around a branch has no seam).
float ValueNoise(double x, double y, uint64_t seed, int period_x = 0);
// Sum of `octaves` value noises at doubling frequencies, normalised to [0, 1].
float FractalNoise(double x, double y, uint64_t seed, int octaves, int period_x = 0);

// A point on a branch's surface: rest arc length from the base, angle around the axis (radians,
// from the branch frame's u towards w), the branch radius there.
struct BarkPoint {
  double arc_length_m = 0.0;
  double angle_rad = 0.0;
  double radius_m = 0.01;
  int branch = 0;
};
// Grey-brown bark, darker fissures running along the branch; thin twigs smoother and browner.
Rgb BarkAlbedo(const BarkPoint& point, uint64_t seed);
// Red tape (slightly uneven), `offset_m` from the band's centre along the branch.
Rgb TapeAlbedo(double angle_rad, double offset_m, uint64_t seed);
// Winter lawn: dull green and straw-coloured grass with patches of bare soil.
Rgb GroundAlbedo(double x, double y, uint64_t seed);
// An evergreen hedge; `along_m` runs along it, `z` is the height.
Rgb HedgeAlbedo(double along_m, double z, uint64_t seed);
// A pale hemp rope with a twisted pattern.
Rgb RopeAlbedo(double along_m);
// Small twigs of a shrub: grey-brown, no streaks.
Rgb ShrubAlbedo(double along_m, uint64_t seed);
// The sky seen along a world direction: pale at the horizon, blue at the zenith (linear colour,
// not shaded).
Rgb SkyColor(const Eigen::Vector3d& direction_world);

}  // namespace simtree::synth
