#include "simtree/dynamics/oscillator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "simtree/core/error.h"
#include "simtree/core/units.h"

namespace simtree::dynamics {
namespace {

struct Decay {
  std::vector<double> t, q, v;
};

Decay FreeDecay(double f, double zeta, double dt, double duration, Integrator integrator,
                double q0 = 1.0) {
  const OscillatorStep s = MakeOscillatorStep(f, zeta, dt, integrator);
  Decay d;
  double q = q0, v = 0;
  const int n = static_cast<int>(std::lround(duration / dt));
  for (int i = 0; i <= n; ++i) {
    d.t.push_back(i * dt);
    d.q.push_back(q);
    d.v.push_back(v);
    s.Apply(0.0, q, v);
  }
  return d;
}

// Times where v changes sign from + to - or - to +, linearly interpolated: the extrema of q.
std::vector<double> VelocityZeroCrossings(const Decay& d) {
  std::vector<double> out;
  for (size_t i = 1; i < d.v.size(); ++i) {
    if ((d.v[i - 1] < 0) != (d.v[i] < 0) && d.v[i - 1] != 0) {
      const double a = d.v[i - 1] / (d.v[i - 1] - d.v[i]);
      out.push_back(d.t[i - 1] + a * (d.t[i] - d.t[i - 1]));
    }
  }
  return out;
}

TEST(Oscillator, ExactFreeDecayHasTheSetFrequencyAndEnvelope) {
  for (double dt : {1.0 / 30, 1.0 / 240}) {
    const double f = 1.6, zeta = 0.02, w = kTwoPi * f;
    const Decay d = FreeDecay(f, zeta, dt, 20.0, Integrator::kExact);
    // Released from rest, the extrema are at t_n = n pi / wd and equal q0 e^(-zeta w t_n).
    const double wd = w * std::sqrt(1 - zeta * zeta);
    const std::vector<double> extrema = VelocityZeroCrossings(d);
    ASSERT_GT(extrema.size(), 30u);
    const double half_periods = static_cast<double>(extrema.size() - 1);
    const double period = 2.0 * (extrema.back() - extrema.front()) / half_periods;
    EXPECT_NEAR(period, kTwoPi / wd, 1e-3 * kTwoPi / wd) << "dt " << dt;
    // Within 0.1% of the undamped 1 / f too: light damping barely shifts it.
    EXPECT_NEAR(period, 1.0 / f, 1e-3 / f);
    // Envelope, evaluated exactly at the analytic extrema by stepping there.
    for (int n = 1; n <= 30; n += 7) {
      const double tn = n * kPi / wd;
      const OscillatorStep to_tn = MakeOscillatorStep(f, zeta, tn, Integrator::kExact);
      double q = 1.0, v = 0.0;
      to_tn.Apply(0.0, q, v);
      EXPECT_NEAR(std::abs(q), std::exp(-zeta * w * tn), 1e-2 * std::exp(-zeta * w * tn));
      EXPECT_NEAR(std::abs(q), std::exp(-zeta * w * tn), 1e-12);
      EXPECT_NEAR(v, 0.0, 1e-10);
    }
  }
}

TEST(Oscillator, ExactIsExactOverManySteps) {
  // Composing steps of dt gives the same state as one step of the whole time.
  const double f = 3.0, zeta = 0.05, dt = 0.01;
  const OscillatorStep small = MakeOscillatorStep(f, zeta, dt, Integrator::kExact);
  const OscillatorStep whole = MakeOscillatorStep(f, zeta, 100 * dt, Integrator::kExact);
  double q1 = 0.3, v1 = -2.0, q2 = 0.3, v2 = -2.0;
  for (int i = 0; i < 100; ++i) small.Apply(5.0, q1, v1);
  whole.Apply(5.0, q2, v2);
  EXPECT_NEAR(q1, q2, 1e-12);
  EXPECT_NEAR(v1, v2, 1e-11);
}

TEST(Oscillator, ConstantForceSettlesAtForceOverStiffness) {
  for (Integrator integrator : {Integrator::kExact, Integrator::kSemiImplicitEuler}) {
    const double f = 2.0, zeta = 0.1, mass = 3.0, force = 12.0;
    const double k = ModalStiffness(mass, f);
    const OscillatorStep s = MakeOscillatorStep(f, zeta, 0.005, integrator);
    double q = 0, v = 0;
    for (int i = 0; i < 20000; ++i) s.Apply(force / mass, q, v);
    EXPECT_NEAR(q, force / k, 1e-9 * force / k) << ToString(integrator);
  }
}

TEST(Oscillator, CriticalAndOverDampedMatchTheirClosedForms) {
  const double f = 1.0, w = kTwoPi * f, t = 0.37;
  // Critical: q = (1 + w t) e^(-w t) from q0 = 1 at rest.
  {
    const OscillatorStep s = MakeOscillatorStep(f, 1.0, t, Integrator::kExact);
    double q = 1, v = 0;
    s.Apply(0.0, q, v);
    EXPECT_NEAR(q, (1 + w * t) * std::exp(-w * t), 1e-12);
  }
  // Over-damped zeta = 2: roots r1,2 = -w (zeta -+ sqrt(zeta^2 - 1)).
  {
    const double zeta = 2.0, g = w * std::sqrt(zeta * zeta - 1);
    const double r1 = -zeta * w + g, r2 = -zeta * w - g;
    const double c1 = -r2 / (r1 - r2), c2 = r1 / (r1 - r2);  // q0 = 1, v0 = 0
    const OscillatorStep s = MakeOscillatorStep(f, zeta, t, Integrator::kExact);
    double q = 1, v = 0;
    s.Apply(0.0, q, v);
    EXPECT_NEAR(q, c1 * std::exp(r1 * t) + c2 * std::exp(r2 * t), 1e-12);
    // A step a million times longer neither overflows nor leaves rest.
    const OscillatorStep huge = MakeOscillatorStep(f, zeta, 1e6, Integrator::kExact);
    double q2 = 1, v2 = 0;
    huge.Apply(0.0, q2, v2);
    EXPECT_TRUE(std::isfinite(q2) && std::isfinite(v2));
    EXPECT_NEAR(q2, 0.0, 1e-12);
  }
  // Just next to critical, where the series takes over, the answer is continuous.
  const OscillatorStep a = MakeOscillatorStep(f, 1.0 - 1e-9, t, Integrator::kExact);
  const OscillatorStep b = MakeOscillatorStep(f, 1.0 + 1e-9, t, Integrator::kExact);
  EXPECT_NEAR(a.a11, b.a11, 1e-9);
  EXPECT_NEAR(a.a12, b.a12, 1e-9);
}

TEST(Oscillator, ExplicitEulerDivergesWhereExactStaysBounded) {
  // A 10 Hz twig at 30 steps per second: w dt = 2.1.
  const double f = 10.0, zeta = 0.02, dt = 1.0 / 30;
  const Decay exact = FreeDecay(f, zeta, dt, 10.0, Integrator::kExact);
  const Decay euler = FreeDecay(f, zeta, dt, 10.0, Integrator::kExplicitEuler);
  const Decay demo = FreeDecay(f, zeta, dt, 10.0, Integrator::kSemiImplicitEuler);
  double exact_max = 0;
  for (double q : exact.q) exact_max = std::max(exact_max, std::abs(q));
  EXPECT_LE(exact_max, 1.0 + 1e-12);
  EXPECT_LT(std::abs(exact.q.back()), 1e-3);  // decayed as e^(-zeta w t)
  EXPECT_GT(std::abs(euler.q.back()), 1e6);   // explicit Euler blew up
  EXPECT_GT(std::abs(demo.q.back()), 1e6);    // so did the demo's semi-implicit Euler (w dt > 2)
  // Even undamped explicit Euler at a gentle 1 Hz grows: energy x (1 + w^2 dt^2) per step.
  const Decay slow = FreeDecay(1.0, 0.0, dt, 60.0, Integrator::kExplicitEuler);
  EXPECT_GT(std::abs(slow.q.back()) + std::abs(slow.v.back()) / kTwoPi, 1.5);
}

TEST(Oscillator, ExactEnergyNeverGrowsWithoutForce) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (double f : {0.1, 1.0, 10.0, 200.0}) {
    for (double zeta : {0.0, 0.02, 0.7, 1.0, 3.0}) {
      for (double dt : {1e-4, 1.0 / 30, 1.0, 100.0}) {
        const OscillatorStep s = MakeOscillatorStep(f, zeta, dt, Integrator::kExact);
        double q = uniform(rng), v = uniform(rng) * kTwoPi * f;
        double energy = OscillatorEnergy(1.0, f, q, v);
        const double start = energy;
        for (int i = 0; i < 300; ++i) {
          s.Apply(0.0, q, v);
          const double next = OscillatorEnergy(1.0, f, q, v);
          ASSERT_LE(next, energy * (1 + 1e-10) + 1e-300)
              << "f " << f << " zeta " << zeta << " dt " << dt << " step " << i;
          energy = next;
        }
        // Undamped: energy is kept, not lost.
        if (zeta == 0.0) {
          EXPECT_NEAR(energy, start, 1e-8 * start) << f << " " << dt;
        }
      }
    }
  }
}

TEST(Oscillator, RejectsNonPhysicalParameters) {
  EXPECT_THROW(MakeOscillatorStep(0.0, 0.02, 0.01, Integrator::kExact), InputError);
  EXPECT_THROW(MakeOscillatorStep(-1.0, 0.02, 0.01, Integrator::kExact), InputError);
  EXPECT_THROW(MakeOscillatorStep(NAN, 0.02, 0.01, Integrator::kExact), InputError);
  EXPECT_THROW(MakeOscillatorStep(1.0, -0.1, 0.01, Integrator::kExact), InputError);
  EXPECT_THROW(MakeOscillatorStep(1.0, NAN, 0.01, Integrator::kExact), InputError);
  EXPECT_THROW(MakeOscillatorStep(1.0, 0.02, 0.0, Integrator::kExact), InputError);
  EXPECT_THROW(MakeOscillatorStep(1.0, 0.02, INFINITY, Integrator::kExact), InputError);
  EXPECT_EQ(ParseIntegrator("exact"), Integrator::kExact);
  EXPECT_EQ(ParseIntegrator("explicit-euler"), Integrator::kExplicitEuler);
  EXPECT_THROW(ParseIntegrator("rk4"), InputError);
}

}  // namespace
}  // namespace simtree::dynamics
