// Base excitation must not create energy: a child swinging on its parent's motion draws its
// energy from the parent, whatever the materials say (a child tuned to its parent, heavy or
// light, on a parent that bends or twists fast).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "dynamics/dynamics_fixtures.h"
#include "simtree/dynamics/tree_dynamics.h"

namespace simtree::dynamics {
namespace {

double LargestDisplacement(const TreeDynamics& sim, const Tree& tree) {
  double largest = 0.0;
  int i = 0;
  for (const Branch& b : tree.branches) {
    for (const Node& n : b.nodes) {
      largest = std::max(largest, (sim.node_positions()[i++].cast<double>() - n.position).norm());
    }
  }
  return largest;
}

// Steps `seconds` at 1/120 s; returns the largest total energy seen, and checks every branch's
// coordinates stay finite.
double RunAndTrackEnergy(TreeDynamics& sim, double seconds) {
  double energy = sim.Energy();
  const int steps = static_cast<int>(std::lround(seconds * 120));
  for (int i = 0; i < steps; ++i) {
    sim.Step(1.0 / 120);
    energy = std::max(energy, sim.Energy());
  }
  for (int b = 0; b < sim.branch_count(); ++b) {
    for (double q : sim.modal_state(b).q) EXPECT_TRUE(std::isfinite(q)) << b;
  }
  return energy;
}

TEST(SwingEnergy, AHeavyChildTunedToItsParentCreatesNoEnergy) {
  // A parent bent and let go, with a child at its tip at the parent's own frequency and half its
  // modal mass. The one-way drive alone rang the child up to 23 times the energy let go.
  Tree tree;
  tree.branches.push_back(test::StraightBranch(0, -1, 0, {0, 0, 0}, {0, 0, 1}, 2.0, 21, 0.05));
  tree.branches.push_back(test::StraightBranch(1, 0, 20, {0, 0, 2}, {1, 0, 0.3}, 0.6, 7, 0.01));
  AssignLevels(tree);
  ComputeFrames(tree);
  tree.branches[0].material =
      Material::FromFrequencyDampingStiffness(1.5, 0.03, 1000, MaterialSource::kMeasured);
  tree.branches[1].material =
      Material::FromFrequencyDampingStiffness(1.5, 0.03, 500, MaterialSource::kMeasured);
  TreeDynamics sim(tree);
  ModalState bent;
  bent.q = {0.1, 0.05, 0.0};
  sim.SetModalState(0, bent);
  const double released = sim.Energy();
  EXPECT_LE(RunAndTrackEnergy(sim, 20.0), released * (1 + 1e-9));
  EXPECT_LT(sim.Energy(), 0.05 * released);
  // The child still swings: its base's motion bends it.
  TreeDynamics again(tree);
  again.SetModalState(0, bent);
  double swing = 0.0;
  for (int i = 0; i < 240; ++i) {
    again.Step(1.0 / 120);
    swing = std::max(swing, std::hypot(again.modal_state(1).q[0], again.modal_state(1).q[1]));
  }
  EXPECT_GT(swing, 0.01);
}

TEST(SwingEnergy, SoftLightTwigsOnAReleasedParentStayBounded) {
  // Thirty very soft, light twigs (2 N/m, 23 g of modal mass each; the parent 11 kg) tuned to
  // their parent, as a simulation-ready tree's interpolated twigs are: pulled, held still and
  // let go, the tree must only lose energy. The one-way drive rang the twigs up to twice the
  // energy let go, their tips 0.93 m out on a parent whose tip was held 0.11 m out.
  const Tree tree = test::TunedTwigTree(30, 2.0);
  TreeDynamics sim(tree);
  Rope rope;
  rope.branch = 0;
  rope.anchor = tree.branches[0].tip().position + Eigen::Vector3d(1e4, 0, 0);
  rope.force_n = 100.0;
  sim.AttachRope(rope);
  sim.SettleStatic();
  const double held = LargestDisplacement(sim, tree);
  sim.ReleaseAllRopes();
  const double released = sim.Energy();
  double largest = 0.0, twig_swing = 0.0;
  double energy = released;
  for (int i = 0; i < 20 * 120; ++i) {
    sim.Step(1.0 / 120);
    energy = std::max(energy, sim.Energy());
    largest = std::max(largest, LargestDisplacement(sim, tree));
    for (int b = 1; b < tree.size(); ++b) {
      twig_swing =
          std::max(twig_swing, std::hypot(sim.modal_state(b).q[0], sim.modal_state(b).q[1]));
    }
  }
  EXPECT_LE(energy, released * (1 + 1e-9));
  EXPECT_LT(sim.Energy(), 0.05 * released);
  // They still swing, and may whip past where they were held (a light twig on a branch let go
  // does), but only on energy their parent had: at most its whole energy in one twig.
  EXPECT_GT(twig_swing, 0.05);
  EXPECT_LT(largest, held + std::sqrt(2.0 * released / 2.0));
}

TEST(SwingEnergy, AFastTwistingParentCannotPumpItsChild) {
  // A parent twisting fast about its axis (0.5 rad at 4 Hz: its tip turns at up to 13 rad/s)
  // swings a horizontal child round at the child's own frequency. The one-way drive rang it up
  // to 400 times the energy let go.
  Tree tree;
  tree.branches.push_back(test::StraightBranch(0, -1, 0, {0, 0, 0}, {0, 0, 1}, 2.0, 21, 0.05));
  tree.branches.push_back(test::StraightBranch(1, 0, 20, {0, 0, 2}, {1, 0, 0}, 1.0, 11, 0.02));
  AssignLevels(tree);
  ComputeFrames(tree);
  tree.branches[0].material =
      Material::FromFrequencyDampingStiffness(4.0, 0.02, 5000, MaterialSource::kMeasured);
  tree.branches[1].material =
      Material::FromFrequencyDampingStiffness(4.0, 0.02, 3000, MaterialSource::kMeasured);
  TreeDynamics sim(tree);
  ModalState twisted;
  twisted.q = {0.0, 0.0, 0.5};
  sim.SetModalState(0, twisted);
  const double released = sim.Energy();
  EXPECT_LE(RunAndTrackEnergy(sim, 15.0), released * (1 + 1e-9));
  EXPECT_LT(sim.Energy(), 0.05 * released);
}

}  // namespace
}  // namespace simtree::dynamics
