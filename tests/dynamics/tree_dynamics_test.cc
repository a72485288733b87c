#include "simtree/dynamics/tree_dynamics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "dynamics/dynamics_fixtures.h"
#include "simtree/core/error.h"
#include "simtree/core/units.h"
#include "simtree/dynamics/detail/mode_shapes.h"

namespace simtree::dynamics {
namespace {

Eigen::Vector3d Tip(const TreeDynamics& sim, int branch) {
  const int last =
      sim.node_offset(branch) + static_cast<int>(sim.tree().branches[branch].nodes.size()) - 1;
  return sim.node_positions()[last].cast<double>();
}

Eigen::Vector3d Node(const TreeDynamics& sim, int branch, int node) {
  return sim.node_positions()[sim.node_offset(branch) + node].cast<double>();
}

Rope HorizontalPull(const Tree& tree, int branch, const Eigen::Vector3d& direction, double force) {
  Rope rope;
  rope.branch = branch;
  rope.anchor = tree.branches[branch].tip().position + 1e4 * direction.normalized();
  rope.force_n = force;
  return rope;
}

TEST(TreeDynamics, StartsAtRestOnTheRestGeometry) {
  const Tree tree = test::ThreeLevelTree();
  TreeDynamics sim(tree);
  ASSERT_EQ(sim.node_count(), tree.NodeCount());
  for (const Branch& b : tree.branches) {
    for (size_t j = 0; j < b.nodes.size(); ++j) {
      EXPECT_LT((Node(sim, b.id, static_cast<int>(j)) - b.nodes[j].position).norm(), 1e-6);
    }
  }
  sim.Advance(1.0, 1.0 / 60);
  EXPECT_EQ(sim.Energy(), 0.0);
  EXPECT_LT((Tip(sim, 2) - tree.branches[2].tip().position).norm(), 1e-6);
}

TEST(TreeDynamics, StaticTipForceDeflectsByForceOverStiffness) {
  const double f = 1.6, zeta = 0.05, k = 5000, force = 80;
  const Tree tree = test::SingleBranchTree(f, zeta, k);
  const Eigen::Vector3d u = tree.branches[0].frame.u, w = tree.branches[0].frame.w;
  for (const Eigen::Vector3d& dir : {u, w, Eigen::Vector3d((u + w).normalized())}) {
    TreeDynamics sim(tree);
    sim.AttachRope(HorizontalPull(tree, 0, dir, force));
    sim.SettleStatic();
    const Eigen::Vector3d moved = Tip(sim, 0) - tree.branches[0].tip().position;
    EXPECT_NEAR(moved.dot(dir), force / k, 1e-6 * force / k);
    EXPECT_NEAR((moved - moved.dot(dir) * dir).norm(), 0.0, 1e-6);
    // Held long enough, the dynamic answer settles at the same place (exact integrator).
    TreeDynamics held(tree);
    held.AttachRope(HorizontalPull(tree, 0, dir, force));
    held.Advance(30.0, 1.0 / 30);
    const Eigen::Vector3d moved_held = Tip(held, 0) - tree.branches[0].tip().position;
    EXPECT_NEAR(moved_held.dot(dir), force / k, 1e-3 * force / k);
  }
}

TEST(TreeDynamics, MidSpanForceFollowsTheModeShape) {
  // One mode: a force F at x bends the tip by phi(x) F / k and the point by phi(x)^2 F / k.
  const double k = 3000, force = 50;
  const Tree tree = test::SingleBranchTree(2.0, 0.03, k, 2.0, 41);
  TreeDynamics sim(tree);
  Rope rope = HorizontalPull(tree, 0, tree.branches[0].frame.u, force);
  rope.arc_length = 1.0;
  sim.AttachRope(rope);
  sim.SettleStatic();
  const double phi = BendingModeShape(0.5);
  EXPECT_NEAR(sim.modal_state(0).q[0], phi * force / k, 1e-6 * force / k);
  const Eigen::Vector3d mid = sim.PointPosition(0, 1.0) - tree.branches[0].PointAt(1.0);
  EXPECT_NEAR(mid.norm(), phi * phi * force / k, 1e-6 * force / k);
}

TEST(TreeDynamics, FreeDecayAfterReleaseHasTheSetPeriodAndEnvelope) {
  const double f = 1.6, zeta = 0.02, k = 5000, force = 100, fps = 30;
  const Tree tree = test::SingleBranchTree(f, zeta, k);
  TreeDynamics sim(tree);
  const Eigen::Vector3d u = tree.branches[0].frame.u;
  const int rope = sim.AttachRope(HorizontalPull(tree, 0, u, force));
  sim.SettleStatic();
  sim.ReleaseRope(rope);
  std::vector<double> t, x;
  for (int i = 0; i <= 20 * fps; ++i) {
    t.push_back(i / fps);
    x.push_back((Tip(sim, 0) - tree.branches[0].tip().position).dot(u));
    sim.Step(1.0 / fps);
  }
  // Period from upward zero crossings (linear interpolation) over the whole record.
  std::vector<double> crossings;
  for (size_t i = 1; i < x.size(); ++i) {
    if (x[i - 1] < 0 && x[i] >= 0) {
      crossings.push_back(t[i - 1] + x[i - 1] / (x[i - 1] - x[i]) / fps);
    }
  }
  ASSERT_GE(crossings.size(), 25u);
  const double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  const double w = kTwoPi * f, wd = w * std::sqrt(1 - zeta * zeta);
  EXPECT_NEAR(period, kTwoPi / wd, 1e-3 * kTwoPi / wd);
  EXPECT_NEAR(period, 1.0 / f, 1e-3 / f);
  // Envelope: the extrema (parabola through the three samples around each) against
  // (F/k) e^(-zeta w t).
  int checked = 0;
  for (size_t i = 1; i + 1 < x.size(); ++i) {
    if (std::abs(x[i]) >= std::abs(x[i - 1]) && std::abs(x[i]) > std::abs(x[i + 1])) {
      const double a = 0.5 * (x[i - 1] - 2 * x[i] + x[i + 1]);
      const double b = 0.5 * (x[i + 1] - x[i - 1]);
      const double offset = -b / (2 * a);
      const double peak = x[i] - b * b / (4 * a);
      const double tp = t[i] + offset / fps;
      const double expected = force / k * std::exp(-zeta * w * tp);
      EXPECT_NEAR(std::abs(peak), expected, 1e-2 * expected) << "t " << tp;
      ++checked;
    }
  }
  EXPECT_GE(checked, 50);
}

TEST(TreeDynamics, LoadsSuperpose) {
  const Tree tree = test::ThreeLevelTree();
  const Rope a = HorizontalPull(tree, 2, {0, 0, -1}, 3.0);
  Rope b = HorizontalPull(tree, 3, {0, 1, 0}, 8.0);
  b.arc_length = 0.6;
  TreeDynamics only_a(tree), only_b(tree), both(tree);
  only_a.AttachRope(a);
  only_b.AttachRope(b);
  both.AttachRope(a);
  both.AttachRope(b);
  // Statically.
  for (TreeDynamics* sim : {&only_a, &only_b, &both}) sim->SettleStatic();
  double largest = 0, worst = 0;
  const TreeDynamics at_rest(tree);
  for (int i = 0; i < both.node_count(); ++i) {
    const Eigen::Vector3f rest = at_rest.node_positions()[i];
    const Eigen::Vector3f da = only_a.node_positions()[i] - rest;
    const Eigen::Vector3f db = only_b.node_positions()[i] - rest;
    const Eigen::Vector3f dab = both.node_positions()[i] - rest;
    largest = std::max(largest, static_cast<double>(dab.norm()));
    worst = std::max(worst, static_cast<double>((dab - da - db).norm()));
  }
  EXPECT_GT(largest, 1e-3);
  EXPECT_LT(worst, 2e-3 * largest);
  // Dynamically: pull from rest for 2 s, release one, 3 s more. Without the swings: a family's
  // swings take no more energy than their parent's damping gives them (modal_step.h), which is
  // not linear once it binds, as it does for these heavy children pulled from rest.
  DynamicsOptions linear;
  linear.base_excitation = false;
  TreeDynamics da(tree, linear), db(tree, linear), dab(tree, linear);
  const int ra = da.AttachRope(a);
  db.AttachRope(b);
  const int rab = dab.AttachRope(a);
  dab.AttachRope(b);
  // Per branch and mode: the largest amplitude and the largest departure from the sum.
  std::vector<std::array<double, 3>> amplitude(tree.size(), {0, 0, 0}),
      error(tree.size(), {0, 0, 0});
  for (int i = 0; i < 300; ++i) {
    if (i == 120) {
      da.ReleaseRope(ra);
      dab.ReleaseRope(rab);
    }
    for (TreeDynamics* sim : {&da, &db, &dab}) sim->Step(1.0 / 60);
    for (int br = 0; br < tree.size(); ++br) {
      for (int m = 0; m < 3; ++m) {
        const double sum = da.modal_state(br).q[m] + db.modal_state(br).q[m];
        amplitude[br][m] = std::max(amplitude[br][m], std::abs(dab.modal_state(br).q[m]));
        error[br][m] = std::max(error[br][m], std::abs(dab.modal_state(br).q[m] - sum));
      }
    }
  }
  // Linear up to the small change of geometry one load makes for the other (and rounding: a
  // straight branch pulled across its axis does not twist).
  for (int br = 0; br < tree.size(); ++br) {
    for (int m = 0; m < 3; ++m) {
      EXPECT_GT(amplitude[br][m], 0.0);
      EXPECT_LT(error[br][m], 5e-3 * amplitude[br][m] + 1e-12) << "branch " << br << " mode " << m;
    }
  }
}

TEST(TreeDynamics, ChildRidesItsParentsDeformedFrame) {
  // A vertical trunk bent by q along u: the child at the tip is carried to the bent tip and
  // turned by the tip slope phi'(1) q / L about -w.
  Tree tree;
  tree.branches.push_back(test::StraightBranch(0, -1, 0, {0, 0, 0}, {0, 0, 1}, 2.0, 21, 0.05));
  tree.branches.push_back(test::StraightBranch(1, 0, 20, {0, 0, 2}, {0, 1, 0}, 1.0, 11, 0.02));
  AssignLevels(tree);
  ComputeFrames(tree);
  for (Branch& b : tree.branches) {
    b.material =
        Material::FromFrequencyDampingStiffness(1.5, 0.03, 1000, MaterialSource::kMeasured);
  }
  DynamicsOptions options;
  options.base_excitation = false;
  TreeDynamics sim(tree, options);
  const Eigen::Vector3d u = tree.branches[0].frame.u, w = tree.branches[0].frame.w;
  ModalState bent;
  bent.q = {0.1, 0.0, 0.0};
  sim.SetModalState(0, bent);
  const Eigen::Vector3d trunk_tip = Eigen::Vector3d(0, 0, 2) + 0.1 * u;
  EXPECT_LT((Tip(sim, 0) - trunk_tip).norm(), 1e-6);
  EXPECT_LT((Node(sim, 1, 0) - trunk_tip).norm(), 1e-6);
  const double angle = BendingModeSlope(1.0) * 0.1 / 2.0;
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(angle, -w).toRotationMatrix();
  const Eigen::Vector3d child_tip = trunk_tip + turn * Eigen::Vector3d(0, 1, 0);
  EXPECT_LT((Tip(sim, 1) - child_tip).norm(), 1e-6);
  EXPECT_TRUE(sim.pose(1).rotation.isApprox(turn, 1e-9));
  EXPECT_TRUE(sim.NodeRotation(0, 20).isApprox(turn, 1e-9));
  // Twist of the trunk turns the child about the trunk axis.
  ModalState twisted;
  twisted.q = {0.0, 0.0, 0.2};
  sim.SetModalState(0, twisted);
  const Eigen::Matrix3d twist = Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_LT((Tip(sim, 1) - (Eigen::Vector3d(0, 0, 2) + twist * Eigen::Vector3d(0, 1, 0))).norm(),
            1e-6);
}

TEST(TreeDynamics, ChildOnAShakenParentMovesWithIt) {
  const Tree tree = test::ThreeLevelTree();
  TreeDynamics sim(tree);
  // Shake the trunk near its attachment of branch 1 with an oscillating rope force.
  Rope rope = HorizontalPull(tree, 0, {0, 1, 0}, 0.0);
  rope.arc_length = 2.0;
  const int id = sim.AttachRope(rope);
  double child_energy = 0;
  const Eigen::Vector3d rest_tip = tree.branches[2].tip().position;
  double tip_travel = 0;
  for (int i = 0; i < 600; ++i) {
    const double t = i / 120.0;
    rope.force_n = 400.0 * (1 + std::sin(kTwoPi * 2.0 * t));
    sim.UpdateRope(id, rope);
    sim.Step(1.0 / 120);
    // The children stay attached to their parents' deformed nodes, and turned with them.
    for (int c = 1; c < tree.size(); ++c) {
      const Branch& b = tree.branches[c];
      ASSERT_LT((Node(sim, c, 0) - Node(sim, b.parent, b.parent_node)).norm(), 2e-6);
      ASSERT_TRUE(sim.pose(c).rotation.isApprox(sim.NodeRotation(b.parent, b.parent_node), 1e-9));
    }
    child_energy = std::max(child_energy, sim.BranchEnergy(2));
    tip_travel = std::max(tip_travel, (Tip(sim, 2) - rest_tip).norm());
  }
  // The grandchild is never touched, yet it swings: carried along and excited by its base.
  EXPECT_GT(tip_travel, 1e-3);
  EXPECT_GT(child_energy, 0.0);
  EXPECT_GT(std::abs(sim.modal_state(2).q[0]) + std::abs(sim.modal_state(2).q[1]), 1e-7);
}

TEST(TreeDynamics, PullingATwigBendsEveryAncestor) {
  const Tree tree = test::ThreeLevelTree();
  TreeDynamics sim(tree);
  sim.AttachRope(HorizontalPull(tree, 2, {0, 0, -1}, 20.0));
  sim.SettleStatic();
  for (int b : {0, 1, 2}) {
    const ModalState& s = sim.modal_state(b);
    EXPECT_GT(std::abs(s.q[0]) + std::abs(s.q[1]), 1e-6) << b;
  }
  // Branch 3 is not on the way to the root: untouched.
  EXPECT_EQ(sim.modal_state(3).q[0], 0.0);
  // Without transfer only the twig bends.
  DynamicsOptions options;
  options.transfer_loads = false;
  TreeDynamics alone(tree, options);
  alone.AttachRope(HorizontalPull(tree, 2, {0, 0, -1}, 20.0));
  alone.SettleStatic();
  EXPECT_EQ(alone.modal_state(0).q[0], 0.0);
  EXPECT_GT(std::abs(alone.modal_state(2).q[0]) + std::abs(alone.modal_state(2).q[1]), 1e-6);
}

TEST(TreeDynamics, EnergyNeverGrowsWithoutInput) {
  const Tree tree = test::ThreeLevelTree();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (bool base_excitation : {false, true}) {
    for (double dt : {1.0 / 120, 1.0 / 30, 0.5}) {
      DynamicsOptions options;
      options.base_excitation = base_excitation;
      TreeDynamics sim(tree, options);
      for (int b = 0; b < tree.size(); ++b) {
        ModalState s;
        for (int m = 0; m < 3; ++m) {
          s.q[m] = 0.05 * uniform(rng);
          s.v[m] = 0.5 * uniform(rng);
        }
        sim.SetModalState(b, s);
      }
      double energy = sim.Energy();
      const double start = energy;
      for (int i = 0; i < 2000; ++i) {
        sim.Step(dt);
        const double next = sim.Energy();
        if (base_excitation) {
          // The swings spend what their parents' damping took out earlier: the total can rise
          // again, but never above what the tree started with.
          ASSERT_LE(next, start * (1 + 1e-12)) << "dt " << dt << " step " << i;
        } else {
          ASSERT_LE(next, energy * (1 + 1e-12)) << "dt " << dt << " step " << i;
        }
        energy = next;
      }
      EXPECT_LT(energy, 1e-3 * start);
    }
  }
  // The trunk, which nothing drives, only loses energy, and everything dies out.
  TreeDynamics sim(tree);
  ModalState s;
  s.q = {0.02, -0.01, 0.003};
  sim.SetModalState(0, s);
  double trunk = sim.BranchEnergy(0);
  const double start = sim.Energy();
  for (int i = 0; i < 60 * 120; ++i) {
    sim.Step(1.0 / 60);
    ASSERT_LE(sim.BranchEnergy(0), trunk * (1 + 1e-12));
    ASSERT_LE(sim.Energy(), start * (1 + 1e-12));
    trunk = sim.BranchEnergy(0);
  }
  EXPECT_LT(sim.Energy(), 1e-6 * start);
}

TEST(TreeDynamics, ExplicitEulerBlowsUpWhereTheDefaultDoesNot) {
  Tree tree = test::ThreeLevelTree();
  tree.branches[2].material =
      Material::FromFrequencyDampingStiffness(12.0, 0.02, 400, MaterialSource::kMeasured);
  for (Integrator integrator : {Integrator::kExact, Integrator::kExplicitEuler}) {
    DynamicsOptions options;
    options.integrator = integrator;
    TreeDynamics sim(tree, options);
    const int rope = sim.AttachRope(HorizontalPull(tree, 2, {0, 0, -1}, 10.0));
    sim.Advance(1.0, 1.0 / 30);
    sim.ReleaseRope(rope);
    sim.Advance(10.0, 1.0 / 30);
    const double travel = (Tip(sim, 2) - tree.branches[2].tip().position).norm();
    if (integrator == Integrator::kExact) {
      EXPECT_LT(travel, 0.05);
    } else {
      EXPECT_FALSE(travel < 10.0) << "explicit Euler stayed bounded: " << travel;
    }
  }
}

TEST(TreeDynamics, PullByDisplacementReachesIt) {
  const Tree tree = test::ThreeLevelTree();
  TreeDynamics sim(tree);
  Rope rope;
  rope.branch = 1;
  rope.arc_length = 1.2;
  const Eigen::Vector3d start = tree.branches[1].PointAt(1.2);
  rope.anchor = start + Eigen::Vector3d(0, -3, -4);  // 5 m away, down and sideways
  rope.mode = Rope::Mode::kDisplacement;
  rope.displacement_m = 0.05;
  const int id = sim.AttachRope(rope);
  EXPECT_GT(sim.RopeTension(id), 0.0);
  sim.SettleStatic();
  const Eigen::Vector3d moved = sim.RopePoint(id) - start;
  EXPECT_NEAR(moved.dot(Eigen::Vector3d(0, -0.6, -0.8)), 0.05, 0.05 * 0.02);
}

TEST(TreeDynamics, GravityPreSagIsAnEquilibriumAndMatchesTheBeamFormula) {
  // A horizontal uniform cantilever: Euler-Bernoulli tip sag q L^4 / (8 EI) under its weight.
  const double f = 2.0, k = 2000;
  const Tree tree = test::SingleBranchTree(f, 0.03, k, 2.0, 81, Eigen::Vector3d::UnitX());
  DynamicsOptions options;
  options.gravity = true;
  TreeDynamics sim(tree, options);
  const double sag = tree.branches[0].tip().position.z() - Tip(sim, 0).z();
  // The modal mass of the tip-normalised first mode is a quarter of the beam's mass, and
  // w^2 = beta^4 EI / (rho A L^4).
  const double mass = 4 * tree.branches[0].material->mass_kg;
  const double w = kTwoPi * f;
  const double length = 2.0;
  const double ei = w * w * (mass / length) * std::pow(length, 4) / std::pow(kCantileverBeta1, 4);
  const double beam = (mass * kGravity / length) * std::pow(length, 4) / (8 * ei);
  EXPECT_NEAR(sag, beam, 0.02 * beam);  // one mode is within 1.3% of the beam
  // It is an equilibrium: nothing moves.
  const std::vector<Eigen::Vector3f> before(sim.node_positions().begin(),
                                            sim.node_positions().end());
  sim.Advance(2.0, 1.0 / 60);
  for (size_t i = 0; i < before.size(); ++i) {
    EXPECT_LT((sim.node_positions()[i] - before[i]).norm(), 1e-6);
  }
  sim.Reset();
  EXPECT_NEAR(tree.branches[0].tip().position.z() - Tip(sim, 0).z(), sag, 1e-9);
}

TEST(TreeDynamics, CurvedBranchTwistsUnderAnOffAxisPull) {
  const Tree tree = test::CurvedBranchTree();
  TreeDynamics sim(tree);
  // The arc bows towards +x; pulling its middle along y twists it about its chord.
  Rope rope = HorizontalPull(tree, 0, {0, 1, 0}, 30.0);
  rope.arc_length = 0.5 * tree.branches[0].Length();
  sim.AttachRope(rope);
  sim.SettleStatic();
  EXPECT_GT(std::abs(sim.modal_state(0).q[2]), 1e-5);
}

TEST(TreeDynamics, WindPushesTheTreeDownwindDeterministically) {
  const Tree tree = test::ThreeLevelTree();
  DynamicsOptions options;
  options.wind.enabled = true;
  options.wind.mean_speed_mps = 15.0;
  options.wind.direction = {0, 1, 0};
  options.wind.seed = 11;
  TreeDynamics a(tree, options), b(tree, options);
  options.wind.seed = 12;
  TreeDynamics c(tree, options);
  double mean_y = 0;
  const int steps = 600;
  for (int i = 0; i < steps; ++i) {
    for (TreeDynamics* sim : {&a, &b, &c}) sim->Step(1.0 / 60);
    mean_y += Tip(a, 3).y() - tree.branches[3].tip().position.y();
  }
  mean_y /= steps;
  EXPECT_GT(mean_y, 1e-4);  // downwind on average
  for (int i = 0; i < a.node_count(); ++i) {
    ASSERT_EQ(a.node_positions()[i], b.node_positions()[i]);  // same seed, same motion
  }
  EXPECT_GT((Tip(a, 2) - Tip(c, 2)).norm(), 1e-7);  // another seed, other gusts
  // Off: the tree comes to rest.
  a.SetWindEnabled(false);
  a.Advance(60.0, 1.0 / 30);
  EXPECT_LT(a.Energy(), 1e-9);
}

TEST(TreeDynamics, LiveMaterialEditChangesTheFrequency) {
  const Tree tree = test::SingleBranchTree(1.0, 0.0, 1000);
  TreeDynamics sim(tree);
  Material m = sim.material(0);
  for (ModeKind kind : {ModeKind::kBendU, ModeKind::kBendW, ModeKind::kTwistV}) {
    m.SetFrequency(kind, 2.0);
  }
  sim.SetMaterial(0, m);
  ModalState s;
  s.q = {0.01, 0, 0};
  sim.SetModalState(0, s);
  // Undamped 2 Hz: back where it started after 0.5 s, opposite after 0.25 s.
  sim.Advance(0.25, 0.01);
  EXPECT_NEAR(sim.modal_state(0).q[0], -0.01, 1e-9);
  sim.Advance(0.25, 0.01);
  EXPECT_NEAR(sim.modal_state(0).q[0], 0.01, 1e-9);
  // A bad edit is refused and changes nothing.
  Material bad = m;
  bad.modes[0].frequency_hz = 0.0;
  EXPECT_THROW(sim.SetMaterial(0, bad), InputError);
  EXPECT_EQ(sim.material(0).modes[0].frequency_hz, 2.0);
  EXPECT_THROW(sim.SetMaterial(5, m), InputError);
}

TEST(TreeDynamics, DemoModeSpreadSplitsTheModes) {
  const Tree tree = test::SingleBranchTree(2.0, 0.05, 1000);
  DynamicsOptions options;
  options.demo_mode_spread = true;
  TreeDynamics sim(tree, options);
  EXPECT_NEAR(sim.material(0).modes[0].frequency_hz, 1.9, 1e-12);
  EXPECT_NEAR(sim.material(0).modes[1].frequency_hz, 2.1, 1e-12);
  EXPECT_NEAR(sim.material(0).modes[2].frequency_hz, 2.0, 1e-12);
  EXPECT_NEAR(sim.material(0).modes[0].damping_ratio, 0.06, 1e-12);
  EXPECT_NEAR(sim.material(0).modes[1].damping_ratio, 0.04, 1e-12);
}

TEST(TreeDynamics, ResetReturnsToRestAndDropsRopes) {
  const Tree tree = test::ThreeLevelTree();
  TreeDynamics sim(tree);
  const int rope = sim.AttachRope(HorizontalPull(tree, 1, {0, 0, -1}, 50));
  sim.Advance(1.0, 1.0 / 60);
  EXPECT_GT(sim.Energy(), 0.0);
  sim.Reset();
  EXPECT_FALSE(sim.HasRope(rope));
  EXPECT_EQ(sim.time(), 0.0);
  EXPECT_EQ(sim.Energy(), 0.0);
  sim.Advance(1.0, 1.0 / 60);
  EXPECT_EQ(sim.Energy(), 0.0);
}

TEST(TreeDynamics, ParallelAndSerialAgree) {
  // Enough branches for the level pass to split across threads.
  Tree tree;
  tree.branches.push_back(test::StraightBranch(0, -1, 0, {0, 0, 0}, {0, 0, 1}, 5.0, 101, 0.2));
  for (int i = 1; i <= 1200; ++i) {
    const int parent = i <= 600 ? 0 : i - 600;
    const Branch& p = tree.branches[parent];
    const int node = parent == 0 ? 1 + (i % 99) : 9;
    const Eigen::Vector3d base = p.nodes[node].position;
    tree.branches.push_back(test::StraightBranch(
        i, parent, node, base, {std::cos(i * 2.4), std::sin(i * 2.4), 0.6}, 0.8, 10, 0.02));
  }
  AssignLevels(tree);
  ComputeFrames(tree);
  for (Branch& b : tree.branches) {
    b.material = Material::FromFrequencyDampingStiffness(1.0 + 0.001 * b.id, 0.03, 500 + b.id,
                                                         MaterialSource::kDefault);
  }
  DynamicsOptions serial_options;
  serial_options.max_threads = 1;
  serial_options.wind.enabled = true;
  DynamicsOptions parallel_options = serial_options;
  parallel_options.max_threads = 0;
  TreeDynamics serial(tree, serial_options), parallel(tree, parallel_options);
  for (TreeDynamics* sim : {&serial, &parallel}) {
    sim->AttachRope(HorizontalPull(tree, 700, {0, 0, -1}, 30));
    sim->Advance(1.0, 1.0 / 60);
  }
  for (int i = 0; i < serial.node_count(); ++i) {
    ASSERT_EQ(serial.node_positions()[i], parallel.node_positions()[i]) << i;
  }
}

TEST(TreeDynamics, BadInputIsRefusedClearly) {
  Tree tree = test::ThreeLevelTree();
  {
    TreeDynamics sim(tree);
    Rope rope;
    rope.branch = 9;
    rope.force_n = 1;
    try {
      sim.AttachRope(rope);
      FAIL() << "unknown branch accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("branch id in [0, 3], got 9"), std::string::npos)
          << e.what();
    }
    rope.branch = 1;
    rope.arc_length = 99.0;
    EXPECT_THROW(sim.AttachRope(rope), InputError);
    rope.arc_length = -1;
    rope.force_n = -5;
    EXPECT_THROW(sim.AttachRope(rope), InputError);
    rope.force_n = NAN;
    EXPECT_THROW(sim.AttachRope(rope), InputError);
    EXPECT_THROW(sim.Step(0.0), InputError);
    EXPECT_THROW(sim.Step(-0.01), InputError);
    EXPECT_THROW(sim.Step(NAN), InputError);
    EXPECT_THROW(sim.Advance(-1.0, 0.01), InputError);
  }
  Tree nan_tree = tree;
  nan_tree.branches[2].material->modes[1].damping_ratio = NAN;
  try {
    TreeDynamics sim(nan_tree);
    FAIL() << "NaN damping accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("branches[2].material.modes[1].damping_ratio"),
              std::string::npos)
        << e.what();
  }
  Tree zero = tree;
  zero.branches[1].material->modes[0].frequency_hz = 0.0;
  EXPECT_THROW(TreeDynamics{zero}, InputError);
  Tree bare = tree;
  bare.branches[3].material.reset();
  EXPECT_THROW(TreeDynamics{bare}, InputError);
  EXPECT_THROW(TreeDynamics{Tree{}}, InputError);
  DynamicsOptions options;
  options.wind.mean_speed_mps = -3;
  EXPECT_THROW(TreeDynamics(tree, options), InputError);
}

TEST(DynamicsOptions, ValidateNamesTheBadField) {
  DynamicsOptions o;
  EXPECT_NO_THROW(o.Validate());
  const auto field = [&](auto change) {
    DynamicsOptions bad;
    change(bad);
    return test::InputErrorField([&] { bad.Validate(); });
  };
  EXPECT_EQ(field([](DynamicsOptions& d) { d.integrator = static_cast<Integrator>(9); }),
            "integrator");
  EXPECT_EQ(field([](DynamicsOptions& d) { d.twist_stiffness_ratio = 0.0; }),
            "twist_stiffness_ratio");
  EXPECT_EQ(field([](DynamicsOptions& d) { d.twist_stiffness_ratio = NAN; }),
            "twist_stiffness_ratio");
  EXPECT_EQ(field([](DynamicsOptions& d) { d.max_threads = -1; }), "max_threads");
  EXPECT_EQ(field([](DynamicsOptions& d) { d.wind.grid_cells = 0; }), "grid_cells");
  // The simulation refuses them before building anything.
  o.max_threads = -1;
  EXPECT_THROW(TreeDynamics(test::ThreeLevelTree(), o), InputError);
}

TEST(PullTarget, ParsesBranchAndArcLength) {
  EXPECT_EQ(ParsePullTarget("12").branch, 12);
  EXPECT_LT(ParsePullTarget("12").arc_length, 0.0);
  EXPECT_EQ(ParsePullTarget("3@0.75").branch, 3);
  EXPECT_DOUBLE_EQ(ParsePullTarget("3@0.75").arc_length, 0.75);
  for (const char* bad : {"", "x", "3@", "@1", "-2", "3@-1", "3@nan", "3@1m", "1.5"}) {
    EXPECT_THROW(ParsePullTarget(bad), InputError) << bad;
  }
}

}  // namespace
}  // namespace simtree::dynamics
