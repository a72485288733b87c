// The exported tree stands still under gravity: the whole tree's linearisation about its rest
// pose, M q'' + (K + G) q = 0 (springs K, gravity's stiffness G), has no negative eigenvalue, so
// no hinge combination is an inverted pendulum its springs cannot hold.

#include <algorithm>
#include <cstdio>

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

#include "robots/authors_tree.h"
#include "simtree/robots/detail/joint_space_model.h"
#include "simtree/robots/export_robot.h"
#include "simtree/synth/detail/tree_generator.h"
#include "simtree/synth/species.h"
#include "test_util.h"

namespace simtree::robots {
namespace {

struct LowestMode {
  double eigenvalue = 0.0;  // (rad/s)^2
  std::string hinges;       // the hinges it moves most
};

LowestMode LowestModeOf(const RobotModel& model) {
  const detail::JointSpaceModel linear = detail::LineariseRobotModel(model, model.gravity);
  const int n = static_cast<int>(linear.hinges.size());
  Eigen::MatrixXd stiffness = linear.gravity;
  for (int i = 0; i < n; ++i) {
    const auto& ref = linear.hinges[i];
    stiffness(i, i) += model.segments[ref.segment].hinges[ref.hinge].stiffness;
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(stiffness, linear.mass);
  LowestMode out;
  out.eigenvalue = solver.eigenvalues()(0);
  const Eigen::VectorXd phi = solver.eigenvectors().col(0);
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return std::abs(phi(a)) > std::abs(phi(b)); });
  for (int k = 0; k < std::min(n, 6); ++k) {
    const auto& ref = linear.hinges[order[k]];
    out.hinges += model.segments[ref.segment].hinges[ref.hinge].name + " ";
  }
  return out;
}

// tree01's per-chain springs left one direction negative (-0.68 (rad/s)^2: branch 71's twist with
// its child 91's bending); the floor stiffens the few hinges it moves and leaves the rest.
TEST(GravityStability, AuthorsTree01HasNoNegativeEigenvalue) {
  const Tree tree = test::AuthorsTree01();
  CalibrationReport report;
  const RobotModel model = MakeRobotModel(tree, ExportOptions{}, "tree01", &report);
  const LowestMode lowest = LowestModeOf(model);
  EXPECT_GE(lowest.eigenvalue, 0.0) << "moves most: " << lowest.hinges;
  EXPECT_TRUE(report.gravity_checked);
  EXPECT_GT(report.gravity_stiffened_hinges, 0);
  EXPECT_LT(report.gravity_stiffened_hinges, model.HingeCount() / 4);
  std::printf("tree01: lowest %.4g (rad/s)^2, %d of %d hinges stiffened, largest raise %.3g\n",
              lowest.eigenvalue, report.gravity_stiffened_hinges, model.HingeCount(),
              report.gravity_largest_raise);
}

TEST(GravityStability, SynthTreesHaveNoNegativeEigenvalue) {
  for (const char* preset : {"acer_palmatum", "magnolia", "acer_rubrum"}) {
    synth::GeneratorOptions grow;
    grow.max_branches = 60;
    Tree tree = synth::GenerateTree(synth::SpeciesPreset(preset), 1, grow);
    for (Branch& b : tree.branches) {
      b.material = Material::FromFrequencyDampingStiffness(
          b.is_trunk() ? 2.0 : 1.0, 0.04, b.is_trunk() ? 3000.0 : 40.0, MaterialSource::kAssumed);
    }
    CalibrationReport report;
    const RobotModel model = MakeRobotModel(tree, ExportOptions{}, preset, &report);
    const LowestMode lowest = LowestModeOf(model);
    EXPECT_GE(lowest.eigenvalue, 0.0) << preset << " moves most: " << lowest.hinges;
    std::printf("%s: %d branches, lowest %.4g (rad/s)^2, %d of %d hinges stiffened (%.3g)\n",
                preset, tree.size(), lowest.eigenvalue, report.gravity_stiffened_hinges,
                model.HingeCount(), report.gravity_largest_raise);
  }
}

}  // namespace
}  // namespace simtree::robots
