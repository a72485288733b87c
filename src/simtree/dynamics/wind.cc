#include "simtree/dynamics/wind.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <Eigen/Geometry>

#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/units.h"

namespace simtree::dynamics {
namespace {

void CheckWind(bool ok, const std::string& field, const std::string& message) {
  CheckOption(ok, "wind options", field, message);
}

// von Karman energy spectrum shape (unnormalised): (kL)^4 / (1 + (kL)^2)^(17/6).
double VonKarman(double k, double length) {
  const double kl2 = (k * length) * (k * length);
  return kl2 * kl2 / std::pow(1.0 + kl2, 17.0 / 6.0);
}

Eigen::Vector3d RandomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  for (;;) {
    const Eigen::Vector3d d(normal(rng), normal(rng), normal(rng));
    if (d.norm() > 1e-6) return d.normalized();
  }
}

}  // namespace

void WindOptions::Validate() const {
  CheckWind(std::isfinite(mean_speed_mps) && mean_speed_mps >= 0.0, "mean_speed_mps",
            fmt::format("expected a speed >= 0 m/s, got {}", mean_speed_mps));
  CheckWind(direction.allFinite(), "direction", "expected a finite direction");
  CheckWind(std::isfinite(turbulence_intensity) && turbulence_intensity >= 0.0,
            "turbulence_intensity",
            fmt::format("expected an intensity >= 0, got {}", turbulence_intensity));
  CheckWind(std::isfinite(length_scale_m) && length_scale_m >= 0.0, "length_scale_m",
            fmt::format("expected a length >= 0 m (0 = automatic), got {}", length_scale_m));
  CheckWind(std::isfinite(shear_exponent) && shear_exponent >= 0.0 && shear_exponent <= 1.0,
            "shear_exponent",
            fmt::format("expected an exponent in [0, 1], got {}", shear_exponent));
  CheckWind(modes >= 1 && modes <= 4096, "modes",
            fmt::format("expected 1 to 4096 Fourier modes, got {}", modes));
  CheckWind(grid_cells >= 1 && grid_cells <= 256, "grid_cells",
            fmt::format("expected 1 to 256 lattice cells, got {}", grid_cells));
  CheckWind(std::isfinite(air_density_kg_m3) && air_density_kg_m3 >= 0.0, "air_density_kg_m3",
            fmt::format("expected a density >= 0, got {}", air_density_kg_m3));
  CheckWind(std::isfinite(drag_coefficient) && drag_coefficient >= 0.0, "drag_coefficient",
            fmt::format("expected a coefficient >= 0, got {}", drag_coefficient));
}

WindField::WindField(const WindOptions& options, const Eigen::Vector3d& min_corner,
                     const Eigen::Vector3d& max_corner)
    : options_(options) {
  options.Validate();
  CheckWind(
      min_corner.allFinite() && max_corner.allFinite() && (max_corner - min_corner).minCoeff() >= 0,
      "bounds", "expected finite bounds of the tree");
  const Eigen::Vector3d horizontal(options.direction.x(), options.direction.y(), 0.0);
  mean_direction_ = horizontal.norm() > 1e-9 ? horizontal.normalized() : Eigen::Vector3d::UnitX();

  ground_z_ = min_corner.z();
  top_z_ = std::max(max_corner.z(), ground_z_ + 1e-3);
  const Eigen::Vector3d extent = (max_corner - min_corner).cwiseMax(1e-3);
  cell_ = extent.maxCoeff() / options.grid_cells;
  // One cell of margin: the moving tree leaves its rest box a little.
  grid_origin_ = min_corner - Eigen::Vector3d::Constant(cell_);
  for (int a = 0; a < 3; ++a) {
    grid_size_[a] = static_cast<int>(std::ceil(extent[a] / cell_ - 1e-9)) + 3;
  }
  grid_.assign(static_cast<size_t>(grid_size_.prod()), Eigen::Vector3f::Zero());

  const double length = options.length_scale_m > 0.0
                            ? options.length_scale_m
                            : std::max(1.0, max_corner.z() - min_corner.z());
  const double sigma = options.turbulence_intensity * options.mean_speed_mps;
  // Wave numbers log-spaced from eddies ten times the length scale down to two lattice cells.
  const double k_max = kPi / cell_;
  const double k_min = std::min(0.1 / length, 0.5 * k_max);
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  modes_.resize(options.modes);
  std::vector<double> weight(options.modes);
  double weight_sum = 0.0;
  const double log_ratio = std::log(k_max / k_min);
  for (int n = 0; n < options.modes; ++n) {
    // Stratified in log k, jittered inside each stratum.
    const double f = (n + unit(rng)) / options.modes;
    const double k = k_min * std::exp(f * log_ratio);
    const double dk = k * log_ratio / options.modes;
    weight[n] = VonKarman(k, length) * dk;
    weight_sum += weight[n];
    FourierMode& m = modes_[n];
    const Eigen::Vector3d k_dir = RandomUnit(rng);
    m.wave_vector = k * k_dir;
    Eigen::Vector3d a = RandomUnit(rng);
    a -= a.dot(k_dir) * k_dir;
    m.amplitude = a.norm() > 1e-9 ? a.normalized() : k_dir.unitOrthogonal();
    m.phase = kTwoPi * unit(rng);
    // Eddies of size 1/k turn over in about 1 / (sigma k).
    m.frequency = sigma * k * (0.5 + unit(rng)) * (unit(rng) < 0.5 ? -1.0 : 1.0);
  }
  // Each component of sum A_n a_n cos(.) has variance sum A_n^2 / 6 for random a_n: scale to
  // sigma^2.
  for (int n = 0; n < options.modes; ++n) {
    const double a =
        weight_sum > 0.0 ? std::sqrt(6.0 * sigma * sigma * weight[n] / weight_sum) : 0.0;
    modes_[n].amplitude *= a;
  }
}

Eigen::Vector3d WindField::MeanVelocity(double z) const {
  const double top = options_.mean_speed_mps;
  if (options_.shear_exponent <= 0.0) return top * mean_direction_;
  const double h = std::clamp((z - ground_z_) / (top_z_ - ground_z_), 0.05, 1.0);
  return top * std::pow(h, options_.shear_exponent) * mean_direction_;
}

Eigen::Vector3d WindField::VelocityExact(const Eigen::Vector3d& point, double time_s) const {
  if (!options_.enabled) return Eigen::Vector3d::Zero();
  // Gusts travel with the wind at the top of the crown.
  const Eigen::Vector3d advected = point - options_.mean_speed_mps * mean_direction_ * time_s;
  Eigen::Vector3d u = MeanVelocity(point.z());
  for (const FourierMode& m : modes_) {
    u += m.amplitude * std::cos(m.wave_vector.dot(advected) + m.frequency * time_s + m.phase);
  }
  return u;
}

void WindField::SampleGrid(double time_s) {
  // Lattice points x modes cosines: worth spreading over the cores for big crowns.
  tbb::parallel_for(0, grid_size_.z(), [&](int z) {
    for (int y = 0; y < grid_size_.y(); ++y) {
      for (int x = 0; x < grid_size_.x(); ++x) {
        const Eigen::Vector3d p = grid_origin_ + cell_ * Eigen::Vector3d(x, y, z);
        grid_[(static_cast<size_t>(z) * grid_size_.y() + y) * grid_size_.x() + x] =
            VelocityExact(p, time_s).cast<float>();
      }
    }
  });
}

Eigen::Vector3d WindField::Velocity(const Eigen::Vector3d& point) const {
  if (!options_.enabled || grid_.empty()) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d g = (point - grid_origin_) / cell_;
  int i[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    const double c = std::clamp(g[a], 0.0, grid_size_[a] - 1.000001);
    i[a] = static_cast<int>(c);
    f[a] = c - i[a];
  }
  const int sx = 1, sy = grid_size_.x(), sz = grid_size_.x() * grid_size_.y();
  const size_t base = static_cast<size_t>(i[2]) * sz + static_cast<size_t>(i[1]) * sy + i[0];
  Eigen::Vector3f u = Eigen::Vector3f::Zero();
  for (int c = 0; c < 8; ++c) {
    const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
    const double w = (dx ? f[0] : 1 - f[0]) * (dy ? f[1] : 1 - f[1]) * (dz ? f[2] : 1 - f[2]);
    u += static_cast<float>(w) * grid_[base + dx * sx + dy * sy + dz * sz];
  }
  return u.cast<double>();
}

}  // namespace simtree::dynamics
