#pragma once
// A turbulent wind: a mean wind plus a random, divergence-free velocity field synthesised from
// Fourier modes (random-Fourier-mode turbulence, Kraichnan 1970, "Diffusion by a random velocity
// field"), with a von Karman energy spectrum. Each mode is a plane wave that is advected with the
// mean wind (Taylor's frozen turbulence) and also evolves in place at its own eddy frequency, so
// the field is noise both in space and in time: gusts sweep through the crown and neighbouring
// branches feel correlated but not identical wind.
//
// Evaluating every mode at every branch each step would cost branches x modes cosines, so
// SampleGrid() evaluates the field on a coarse lattice over the crown and Velocity() interpolates
// it; the shortest wavelength is kept at least two lattice cells long so nothing aliases.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace simtree::dynamics {

struct WindOptions {
  bool enabled = false;         // off: no wind load, whatever the rest says
  double mean_speed_mps = 5.0;  // at the top of the crown (m/s, >= 0)
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // blowing towards; made horizontal
  // Standard deviation of each velocity component over mean speed (>= 0; 0.1-0.3 near trees).
  double turbulence_intensity = 0.25;
  // Integral length scale of the gusts (m, >= 0); 0 = the crown's height (at least 1 m).
  double length_scale_m = 0.0;
  // Mean speed grows with height as (z / top)^exponent (power-law boundary layer, exponent in
  // [0, 1]); 0 = uniform.
  double shear_exponent = 0.15;
  int modes = 64;                  // Fourier modes of the turbulence (1 to 4096)
  int grid_cells = 8;              // lattice cells along the longest side of the crown (1 to 256)
  uint64_t seed = 1;               // same seed, same wind
  double air_density_kg_m3 = 1.2;  // kg/m^3, >= 0
  double drag_coefficient = 1.2;   // of a cylinder in cross flow (Re ~ 1e3-1e5), >= 0

  // Throws InputError ("wind options", the field) for a value out of range: a negative or NaN
  // speed, intensity, length, density or coefficient, a shear exponent outside [0, 1], modes or
  // cells outside their ranges, a direction that is not finite.
  void Validate() const;
};

class WindField {
 public:
  WindField() = default;
  // `min_corner`/`max_corner` bound the tree; the lattice covers them. Throws InputError on
  // options out of range (options.Validate()) or bounds that are not finite.
  WindField(const WindOptions& options, const Eigen::Vector3d& min_corner,
            const Eigen::Vector3d& max_corner);

  const WindOptions& options() const { return options_; }

  // The field at a point and time from the Fourier modes directly (exact, slow: for tests and
  // single points).
  Eigen::Vector3d VelocityExact(const Eigen::Vector3d& point, double time_s) const;

  // Fills the lattice at `time_s`; Velocity() then interpolates it (trilinear, clamped to the box).
  void SampleGrid(double time_s);
  Eigen::Vector3d Velocity(const Eigen::Vector3d& point) const;

 private:
  struct FourierMode {
    Eigen::Vector3d wave_vector;  // rad/m
    Eigen::Vector3d amplitude;    // m/s, perpendicular to wave_vector (divergence-free)
    double phase = 0;             // rad
    double frequency = 0;         // rad/s, own evolution besides advection
  };
  Eigen::Vector3d MeanVelocity(double z) const;

  WindOptions options_;
  Eigen::Vector3d mean_direction_ = Eigen::Vector3d::UnitX();
  double ground_z_ = 0, top_z_ = 1;
  std::vector<FourierMode> modes_;
  Eigen::Vector3d grid_origin_ = Eigen::Vector3d::Zero();
  double cell_ = 1.0;
  Eigen::Vector3i grid_size_ = Eigen::Vector3i::Ones();  // lattice points per axis
  std::vector<Eigen::Vector3f> grid_;                    // x fastest
};

}  // namespace simtree::dynamics
