#include "simtree/synth/detail/fem_response.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "synth/fem_test_trees.h"

namespace simtree::synth {
namespace {

using ::testing::HasSubstr;

std::vector<double> Times(double start, double end, double step) {
  std::vector<double> t;
  for (int i = 0; start + i * step <= end + 1e-9; ++i) t.push_back(start + i * step);
  return t;
}

struct CantileverCase {
  double length = 2.0, radius = 0.02;
  Tree tree = test::UniformCantilever({0, 0, 1}, 2.0, 0.02, 20);
};

// Released from its first mode shape, the cantilever swings at the first mode's period: Newmark
// average acceleration lengthens it by about (omega dt)^2 / 12, far below 0.1% at 1/600 s.
TEST(FemResponse, FreeDecayHasTheFirstModesPeriod) {
  const CantileverCase c;
  const FemModel model(c.tree, test::TestWood());
  const ModalBasis modes = ComputeModes(model, {.count = 4});
  FemState start = RestState(model);
  start.x = 0.05 * modes.shapes.col(0);
  const double period = 1.0 / modes.frequency_hz[0];
  const std::vector<double> times = Times(0.0, 5 * period, 1.0 / 600);
  std::vector<double> tip;
  const PointMap tip_map = model.PointMapAt(0, c.length);
  const Eigen::Vector3d direction = tip_map.Apply(start.x).displacement.normalized();
  IntegrateNewmark(model, start, FemLoad{}, times, {}, [&](int, double, const FemState& s) {
    tip.push_back(tip_map.Apply(s.x).displacement.dot(direction));
  });
  ASSERT_EQ(tip.size(), times.size());
  // Downward zero crossings, interpolated linearly.
  std::vector<double> crossings;
  for (size_t i = 1; i < tip.size(); ++i) {
    if (tip[i - 1] > 0 && tip[i] <= 0) {
      crossings.push_back(times[i - 1] +
                          (times[i] - times[i - 1]) * tip[i - 1] / (tip[i - 1] - tip[i]));
    }
  }
  ASSERT_GE(crossings.size(), 4u);
  const double measured = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  EXPECT_NEAR(measured / period, 1.0, 1e-3);
  // And the closed form's period, within 1%.
  const double closed =
      1.0 / test::CantileverFrequencyHz(test::kBetaL1, model.wood(), c.length, c.radius);
  EXPECT_NEAR(measured / closed, 1.0, 1e-2);
}

// With Rayleigh damping the first mode's amplitude follows e^(-zeta omega t) within 1%.
TEST(FemResponse, FreeDecayFollowsTheRayleighEnvelope) {
  const CantileverCase c;
  WoodProperties wood = test::TestWood();
  wood.SetRayleighFromRatios(2.0, 0.04, 20.0, 0.05);
  const FemModel model(c.tree, wood);
  const ModalBasis modes = ComputeModes(model, {.count = 4});
  const double w = modes.omega[0], zeta = modes.damping_ratio[0];
  EXPECT_NEAR(zeta, wood.DampingRatioAt(modes.frequency_hz[0]), 1e-12);
  FemState start = RestState(model);
  start.x = 0.05 * modes.shapes.col(0);
  const Eigen::VectorXd m_phi = model.mass() * modes.shapes.col(0);
  const double wd = w * std::sqrt(1 - zeta * zeta);
  int checked = 0;
  IntegrateNewmark(model, start, FemLoad{}, Times(0.0, 6.0, 0.25), {},
                   [&](int, double t, const FemState& s) {
                     const double q = m_phi.dot(s.x), qd = m_phi.dot(s.v);
                     const double amplitude = std::hypot(q, (qd + zeta * w * q) / wd);
                     EXPECT_NEAR(amplitude / (0.05 * std::exp(-zeta * w * t)), 1.0, 1e-2) << t;
                     ++checked;
                   });
  EXPECT_EQ(checked, 25);
}

// Without load the energy never grows: constant when undamped (the average-acceleration rule
// conserves it exactly for a linear system), falling when damped.
TEST(FemResponse, EnergyNeverGrowsWithoutLoad) {
  for (bool damped : {false, true}) {
    WoodProperties wood = test::TestWood();
    if (damped) wood.SetRayleighFromRatios(1.0, 0.03, 30.0, 0.05);
    const FemModel model(test::YTree(), wood);
    const ModalBasis modes = ComputeModes(model, {.count = 12});
    const FemState start =
        RandomVibrationState(model, modes, {.amplitude_m = 0.01, .mode_count = 12, .seed = 3});
    const double e0 = MechanicalEnergy(model, start);
    ASSERT_GT(e0, 0.0);
    double previous = e0;
    IntegrateNewmark(model, start, FemLoad{}, Times(0.0, 3.0, 1.0 / 600), {},
                     [&](int i, double, const FemState& s) {
                       const double e = MechanicalEnergy(model, s);
                       if (damped) {
                         EXPECT_LE(e, previous * (1 + 1e-12)) << i;
                       } else {
                         EXPECT_NEAR(e / e0, 1.0, 1e-9) << i;
                       }
                       previous = e;
                     });
    if (damped) {
      EXPECT_LT(previous, 0.5 * e0);
    }
  }
}

PullLoad TipPull(const Tree& tree, int branch, double force) {
  PullLoad pull;
  pull.branch = branch;
  pull.arc_length = tree.branches[branch].Length();
  pull.attach_point = tree.branches[branch].tip().position;
  pull.anchor = pull.attach_point + Eigen::Vector3d(2.0, 1.0, -0.5);
  pull.force_n = force;
  pull.ramp_start_s = 0.5;
  pull.hold_start_s = 2.0;
  pull.release_s = 5.0;
  pull.duration_s = 8.0;
  return pull;
}

// A slow pull, a long hold, then the release: the tree is released from its static deflection.
TEST(FemResponse, PullThenReleaseStartsFromTheStaticDeflection) {
  const Tree tree = test::YTree();
  WoodProperties wood = test::TestWood();
  wood.SetRayleighFromRatios(1.0, 0.05, 20.0, 0.05);
  const FemModel model(tree, wood);
  const PullLoad pull = TipPull(tree, 1, 30.0);
  const Eigen::VectorXd x_static =
      SolveStatic(model, model.PointLoad(1, pull.arc_length, pull.force_n * pull.Direction()));
  const std::vector<double> frames = Times(0.0, pull.duration_s, 1.0 / 30);
  int calls = 0;
  double after = 0.0;
  const PullResult run =
      IntegratePull(model, pull, frames, {}, [&](int i, double t, const FemState& s) {
        EXPECT_EQ(i, calls++);
        EXPECT_DOUBLE_EQ(t, frames[i]);
        if (t > pull.release_s + 1.0) after = std::max(after, s.x.norm());
      });
  EXPECT_EQ(calls, static_cast<int>(frames.size()));
  EXPECT_DOUBLE_EQ(run.release_state.time_s, pull.release_s);
  EXPECT_LT((run.release_state.x - x_static).norm(), 1e-2 * x_static.norm());
  EXPECT_LT(run.release_state.v.norm() * 0.1, 1e-2 * x_static.norm());  // nearly at rest
  // After release it swings back and decays.
  EXPECT_GT(after, 0.0);
  EXPECT_LT(after, x_static.norm());
  EXPECT_LE(run.run.time_step_s, 1.0 / 600 + 1e-15);
}

// The modal integrator (modes + the static residual of the rest) follows the direct one.
TEST(FemResponse, ModalIntegrationFollowsTheDirectOne) {
  const Tree tree = test::YTree(0.06, 0.025);
  WoodProperties wood = test::TestWood();
  wood.SetRayleighFromRatios(1.0, 0.03, 20.0, 0.05);
  const FemModel model(tree, wood);
  const ModalBasis modes = ComputeModes(model, {.count = 24});
  const PullLoad pull = TipPull(tree, 2, 20.0);
  const std::vector<double> frames = Times(0.0, 7.0, 1.0 / 30);
  std::vector<Eigen::VectorXd> direct, modal;
  const PullResult a = IntegratePull(
      model, pull, frames, {}, [&](int, double, const FemState& s) { direct.push_back(s.x); });
  // Without rates the samples carry x only, but the release state keeps its velocity.
  const PullResult b = IntegratePull(model, modes, pull, frames, {.sample_rates = false},
                                     [&](int, double, const FemState& s) {
                                       EXPECT_EQ(s.v.size(), 0);
                                       modal.push_back(s.x);
                                     });
  ASSERT_EQ(b.release_state.v.size(), model.dof_count());
  ASSERT_EQ(direct.size(), frames.size());
  ASSERT_EQ(modal.size(), frames.size());
  double largest = 0.0, worst = 0.0;
  for (size_t i = 0; i < frames.size(); ++i) {
    largest = std::max(largest, direct[i].norm());
    worst = std::max(worst, (direct[i] - modal[i]).norm());
  }
  EXPECT_LT(worst, 1e-2 * largest);
  EXPECT_LT((a.release_state.x - b.release_state.x).norm(), 1e-3 * a.release_state.x.norm());
  // Velocities on the scale of omega_1 x.
  EXPECT_LT((a.release_state.v - b.release_state.v).norm(),
            1e-2 * modes.omega[0] * a.release_state.x.norm());
}

TEST(FemResponse, SamplesBetweenStepsAndOnJumps) {
  // Sample times off the step grid still come out in order, and a sample on the release instant
  // sees the held deflection (x is continuous across the cut).
  const Tree tree = test::UniformCantilever({0, 0, 1}, 1.0, 0.02, 10);
  const FemModel model(tree, test::TestWood());
  PullLoad pull = TipPull(tree, 0, 10.0);
  pull.release_s = 2.345678;
  const std::vector<double> frames = {0.0, 0.1234567, 1.0, pull.release_s, 2.5};
  std::vector<double> seen;
  Eigen::VectorXd at_release;
  const PullResult run = IntegratePull(model, pull, frames, {.max_time_step_s = 0.01},
                                       [&](int i, double t, const FemState& s) {
                                         seen.push_back(t);
                                         if (i == 3) at_release = s.x;
                                       });
  EXPECT_EQ(seen, frames);
  EXPECT_LT((at_release - run.release_state.x).norm(), 1e-12 * at_release.norm());
  EXPECT_GT(at_release.norm(), 0.0);
}

TEST(FemResponse, RandomVibrationIsSeededAndScaled) {
  const FemModel model(test::YTree(), test::TestWood());
  const ModalBasis modes = ComputeModes(model, {.count = 8});
  const FemState a = RandomVibrationState(model, modes, {.amplitude_m = 0.004, .seed = 7});
  const FemState b = RandomVibrationState(model, modes, {.amplitude_m = 0.004, .seed = 7});
  const FemState c = RandomVibrationState(model, modes, {.amplitude_m = 0.004, .seed = 8});
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.v, b.v);
  EXPECT_NE(a.x, c.x);
  double largest = 0.0;
  for (int node = 1; node < model.node_count(); ++node) {
    largest = std::max(largest, a.x.segment<3>(model.node_dof(node)).norm());
  }
  EXPECT_NEAR(largest, 0.004, 1e-12);
  // Free vibration from it through the modes stays within the modes it was made of.
  int samples = 0;
  IntegrateFree(model, modes, a, Times(0.0, 1.0, 0.1), {}, [&](int, double, const FemState& s) {
    ++samples;
    EXPECT_LT(s.x.norm(), 10 * a.x.norm());
  });
  EXPECT_EQ(samples, 11);
}

TEST(FemResponse, BadInputIsAnInputError) {
  const Tree tree = test::YTree();
  const FemModel model(tree, test::TestWood());
  const auto ignore = [](int, double, const FemState&) {};
  PullLoad pull = TipPull(tree, 1, 10.0);
  const std::vector<double> frames = {0.0, 1.0};
  pull.branch = 9;
  EXPECT_THAT(test::ErrorOf<InputError>([&] { IntegratePull(model, pull, frames, {}, ignore); }),
              HasSubstr("branch"));
  pull = TipPull(tree, 1, 10.0);
  pull.anchor = pull.attach_point;
  EXPECT_THAT(test::ErrorOf<InputError>([&] { IntegratePull(model, pull, frames, {}, ignore); }),
              HasSubstr("anchor"));
  pull = TipPull(tree, 1, std::numeric_limits<double>::quiet_NaN());
  EXPECT_THAT(test::ErrorOf<InputError>([&] { IntegratePull(model, pull, frames, {}, ignore); }),
              HasSubstr("force_n"));
  pull = TipPull(tree, 1, 10.0);
  pull.release_s = 1.0;  // before the hold starts
  EXPECT_THAT(test::ErrorOf<InputError>([&] { IntegratePull(model, pull, frames, {}, ignore); }),
              HasSubstr("release_s"));
  pull = TipPull(tree, 1, 10.0);
  const std::vector<double> backwards = {1.0, 0.5};
  EXPECT_THAT(test::ErrorOf<InputError>([&] { IntegratePull(model, pull, backwards, {}, ignore); }),
              HasSubstr("ascending"));
  EXPECT_THAT(test::ErrorOf<InputError>(
                  [&] { IntegratePull(model, pull, frames, {.max_time_step_s = 0}, ignore); }),
              HasSubstr("max_time_step_s"));
  FemState start = RestState(model);
  start.x.resize(4);
  EXPECT_THAT(test::ErrorOf<InputError>(
                  [&] { IntegrateNewmark(model, start, FemLoad{}, frames, {}, ignore); }),
              HasSubstr("start.x"));
  EXPECT_THAT(test::ErrorOf<InputError>([&] {
                IntegrateNewmark(model, ModalBasis{}, RestState(model), FemLoad{}, frames, {},
                                 ignore);
              }),
              HasSubstr("modes"));
}

}  // namespace
}  // namespace simtree::synth
