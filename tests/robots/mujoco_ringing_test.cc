// The exported MJCF in MuJoCo: every first-level branch of the authors' tree01 pulled at its tip,
// released, and its ringing read from the simulated trajectory against its material.

#include <cmath>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "robots/authors_tree.h"
#include "simtree/core/units.h"
#include "simtree/robots/export_robot.h"
#include "simtree/robots/mujoco_pull.h"
#include "test_util.h"

namespace simtree::robots {
namespace {

double ModalStiffnessOf(double mass_kg, double frequency_hz) {
  return 4.0 * kPi * kPi * frequency_hz * frequency_hz * mass_kg;
}

double SubtreeMass(const RobotModel& model, int branch, const Tree& tree) {
  double mass = 0.0;
  const auto children = tree.Children();
  std::vector<int> stack = {branch};
  while (!stack.empty()) {
    const int b = stack.back();
    stack.pop_back();
    for (int id : model.branch_segments[b]) mass += model.segments[id].mass_kg;
    for (int c : children[b]) stack.push_back(c);
  }
  return mass;
}

// Pulls `branch` at its tip along its u axis by about 3% of its length, releases it and reads
// the ringing of its tip and of its parent's tip.
struct PulledBranch {
  Ringing own, parent;
};

PulledBranch PullAndRelease(const Tree& tree, const RobotModel& model,
                            const std::filesystem::path& xml, int branch) {
  const Branch& b = tree.branches[branch];
  const double omega = 2 * kPi * b.material->modes[0].frequency_hz;
  const double force = 0.25 * SubtreeMass(model, branch, tree) * omega * omega * 0.03 * b.Length();
  MujocoPullOptions pull;
  pull.pull_site = fmt::format("tip_b{}", branch);
  pull.force = force * b.frame.u;
  pull.hold_s = 0.5;
  pull.release_s = 1.5;
  pull.duration_s = 7.5;
  pull.record_sites = {pull.pull_site, fmt::format("tip_b{}", std::max(b.parent, 0))};
  const MujocoPullResult run = RunMujocoPull(xml, pull);
  return {MeasureRinging(run, 0), MeasureRinging(run, 1)};
}

// One tapered branch on the world: its chain rings in MuJoCo at its material's frequency and
// damping ratio in both bending planes (the per-chain calibration, no coupling to correct).
TEST(MujocoRinging, LoneBranchRingsAtItsMaterial) {
  Tree tree;
  Branch trunk;
  trunk.nodes = {{Eigen::Vector3d(0, 0, 0), 0.05},
                 {Eigen::Vector3d(0.02, 0, 0.8), 0.035},
                 {Eigen::Vector3d(0.05, 0.01, 1.6), 0.02}};
  Material material;
  material.modes = {Mode{ModeKind::kBendU, 1.5, 0.03}, Mode{ModeKind::kBendW, 1.8, 0.05},
                    Mode{ModeKind::kTwistV, 2.0, 0.03}};
  material.mass_kg = 1.0;
  material.stiffness = ModalStiffnessOf(1.0, 1.5);
  trunk.material = material;
  trunk.frame.v = (trunk.tip().position - trunk.base().position).normalized();
  trunk.frame.u = Eigen::Vector3d::UnitY().cross(trunk.frame.v).normalized();
  trunk.frame.w = trunk.frame.u.cross(trunk.frame.v);
  tree.branches = {trunk};
  ExportOptions options;
  const auto xml = test::TempDir() / "lone.xml";
  ExportRobot(tree, options, xml);
  for (const auto& [axis, mode] :
       {std::pair{trunk.frame.u, material.modes[0]}, std::pair{trunk.frame.w, material.modes[1]}}) {
    MujocoPullOptions pull;
    pull.pull_site = "tip_b0";
    pull.force = 20.0 * axis;
    pull.hold_s = 0.5;
    pull.release_s = 1.0;
    pull.duration_s = 7.0;
    pull.record_sites = {"tip_b0"};
    const Ringing ringing = MeasureRinging(RunMujocoPull(xml, pull), 0);
    ASSERT_TRUE(ringing.ok) << ringing.message;
    EXPECT_NEAR(ringing.frequency_hz, mode.frequency_hz, 0.05 * mode.frequency_hz);
    EXPECT_NEAR(ringing.damping_ratio, mode.damping_ratio, 0.15 * mode.damping_ratio);
  }
}

// Disabled: the bar (5% / 15% on every first-level branch) is not met yet. Measured
// (2026-11-29, 4 segments, per-chain calibration with gravity, 1 ms step): branches without heavy
// sub-trees ring within 5% and 15% (10 of 19: 6, 7, 8, 10, 12, 14, 16-19), the others 8-70% off
// (branch 1 at 2.04 Hz for 1.6 Hz, damping 0.046 for 0.02; branch 15's tip rings in a 0.48 Hz
// sub-tree mode). The free tree's two-way coupling (children tuned below their parents swing
// them back) moves the ringing; detail/coupled_tuning.h does not converge on tree01 yet
// (coupled_tuning_test.cc). Run it with --gtest_also_run_disabled_tests to see the numbers.
TEST(MujocoRinging, DISABLED_AuthorsTree01FirstLevelBranchesRingAtTheirMaterials) {
  const Tree tree = test::AuthorsTree01();
  ExportOptions options;
  options.calibration.time_step_s = 0.001;  // stable here (stiffness-proportional damping)
  const auto xml = test::TempDir() / "tree01.xml";
  CalibrationReport calibration;
  const RobotModel model = MakeRobotModel(tree, options, "tree01", &calibration);
  test::WriteText(xml, WriteMjcf(model));
  fmt::print("bodies {} hinges {} dt {} mass {} coupled {} it {} worst f {} zeta {} off {}\n",
             model.segments.size(), model.HingeCount(), model.time_step_s, model.total_mass_kg,
             calibration.coupled, calibration.coupled_iterations, calibration.worst_frequency_error,
             calibration.worst_damping_error, calibration.groups_off);
  std::fflush(stdout);
  for (const Branch& b : tree.branches) {
    if (b.level != 1) continue;
    const PulledBranch r = PullAndRelease(tree, model, xml, b.id);
    const Mode& mode = b.material->modes[0];
    fmt::print(
        "b{:3d} f {:.3f} got {:.3f} ({:+.1f}%)  zeta {:.4f} got {:.4f} ({:+.1f}%)  parent f "
        "{:.3f}\n",
        b.id, mode.frequency_hz, r.own.frequency_hz,
        100 * (r.own.frequency_hz / mode.frequency_hz - 1), mode.damping_ratio, r.own.damping_ratio,
        100 * (r.own.damping_ratio / mode.damping_ratio - 1), r.parent.frequency_hz);
    std::fflush(stdout);
    EXPECT_NEAR(r.own.frequency_hz, mode.frequency_hz, 0.05 * mode.frequency_hz) << b.id;
    EXPECT_NEAR(r.own.damping_ratio, mode.damping_ratio, 0.15 * mode.damping_ratio) << b.id;
  }
}

}  // namespace
}  // namespace simtree::robots
