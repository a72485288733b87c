#include "simtree/dynamics/wind.h"

#include <gtest/gtest.h>

#include <cmath>

#include "dynamics/dynamics_fixtures.h"
#include "simtree/core/error.h"

namespace simtree::dynamics {
namespace {

WindOptions Windy() {
  WindOptions w;
  w.enabled = true;
  w.mean_speed_mps = 6.0;
  w.direction = {0, 1, 0};
  w.turbulence_intensity = 0.3;
  w.shear_exponent = 0.0;
  w.length_scale_m = 3.0;
  w.seed = 5;
  return w;
}

const Eigen::Vector3d kMin(-2, -2, 0), kMax(2, 2, 4);

double Correlation(const WindField& field, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const double t = 0.05 * i;
    const double x = field.VelocityExact(a, t).x(), y = field.VelocityExact(b, t).x();
    sa += x;
    sb += y;
    saa += x * x;
    sbb += y * y;
    sab += x * y;
  }
  const double ma = sa / n, mb = sb / n;
  return (sab / n - ma * mb) / std::sqrt((saa / n - ma * ma) * (sbb / n - mb * mb));
}

TEST(Wind, MeanAndGustStrengthAsAsked) {
  const WindField field(Windy(), kMin, kMax);
  const Eigen::Vector3d p(0.3, -0.2, 2.0);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero(), square = Eigen::Vector3d::Zero();
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d u = field.VelocityExact(p, 0.05 * i);
    mean += u;
    square += u.cwiseProduct(u);
  }
  mean /= n;
  const Eigen::Vector3d sigma = (square / n - mean.cwiseProduct(mean)).cwiseSqrt();
  EXPECT_NEAR(mean.y(), 6.0, 0.6);
  EXPECT_NEAR(mean.x(), 0.0, 0.6);
  // Three components together carry the asked variance (a finite set of modes splits it
  // unevenly between components).
  EXPECT_NEAR(sigma.norm() / std::sqrt(3.0), 0.3 * 6.0, 0.35 * 0.3 * 6.0);
}

TEST(Wind, GustsAreNoiseInSpaceAndTime) {
  const WindField field(Windy(), kMin, kMax);
  const Eigen::Vector3d p(0, 0, 2);
  EXPECT_GT(Correlation(field, p, p + Eigen::Vector3d(0.05, 0, 0)), 0.95);
  EXPECT_LT(Correlation(field, p, p + Eigen::Vector3d(30, 0, 0)), 0.5);
  // Divergence-free: the divergence is small against the velocity gradients.
  const double h = 1e-4;
  double div_sum = 0, grad_sum = 0;
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d q(0.1 * i - 2, 0.03 * i, 0.07 * i);
    double div = 0;
    for (int a = 0; a < 3; ++a) {
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      d[a] = h;
      const Eigen::Vector3d g =
          (field.VelocityExact(q + d, 1.0) - field.VelocityExact(q - d, 1.0)) / (2 * h);
      div += g[a];
      grad_sum += g.norm();
    }
    div_sum += std::abs(div);
  }
  EXPECT_LT(div_sum, 1e-4 * grad_sum);
}

TEST(Wind, LatticeInterpolatesTheField) {
  WindField field(Windy(), kMin, kMax);
  field.SampleGrid(2.5);
  double error = 0, size = 0;
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d q(-1.9 + 0.019 * i, 1.5 - 0.015 * i, 0.02 * i);
    error += (field.Velocity(q) - field.VelocityExact(q, 2.5)).norm();
    size += (field.VelocityExact(q, 2.5) - Eigen::Vector3d(0, 6, 0)).norm();
  }
  EXPECT_LT(error, 0.25 * size);  // gusts resolved, not aliased
}

TEST(Wind, SameSeedSameWindAndOffMeansCalm) {
  const WindField a(Windy(), kMin, kMax), b(Windy(), kMin, kMax);
  WindOptions other = Windy();
  other.seed = 6;
  const WindField c(other, kMin, kMax);
  const Eigen::Vector3d p(1, 1, 1);
  EXPECT_EQ(a.VelocityExact(p, 3.0), b.VelocityExact(p, 3.0));
  EXPECT_NE(a.VelocityExact(p, 3.0), c.VelocityExact(p, 3.0));
  WindOptions off = Windy();
  off.enabled = false;
  EXPECT_EQ(WindField(off, kMin, kMax).VelocityExact(p, 3.0), Eigen::Vector3d::Zero());
  // Shear: slower near the ground than at the top.
  WindOptions sheared = Windy();
  sheared.shear_exponent = 0.2;
  sheared.turbulence_intensity = 0.0;
  const WindField s(sheared, kMin, kMax);
  EXPECT_LT(s.VelocityExact({0, 0, 0.5}, 0).norm(), s.VelocityExact({0, 0, 4}, 0).norm());
  EXPECT_NEAR(s.VelocityExact({0, 0, 4}, 0).y(), 6.0, 1e-9);
}

TEST(Wind, BadOptionsAreRefused) {
  for (auto change : std::initializer_list<void (*)(WindOptions&)>{
           [](WindOptions& w) { w.mean_speed_mps = -1; },
           [](WindOptions& w) { w.mean_speed_mps = NAN; },
           [](WindOptions& w) { w.turbulence_intensity = -0.1; },
           [](WindOptions& w) { w.modes = 0; },
           [](WindOptions& w) { w.grid_cells = 0; },
           [](WindOptions& w) { w.shear_exponent = 2; },
           [](WindOptions& w) {
             w.direction = {NAN, 0, 0};
           },
       }) {
    WindOptions w = Windy();
    change(w);
    EXPECT_THROW(w.Validate(), InputError);
    EXPECT_THROW(WindField(w, kMin, kMax), InputError);
  }
  WindOptions w = Windy();
  w.air_density_kg_m3 = -1;
  EXPECT_EQ(test::InputErrorField([&] { w.Validate(); }), "air_density_kg_m3");
  w = Windy();
  w.length_scale_m = INFINITY;
  EXPECT_EQ(test::InputErrorField([&] { w.Validate(); }), "length_scale_m");
  EXPECT_NO_THROW(Windy().Validate());
}

}  // namespace
}  // namespace simtree::dynamics
