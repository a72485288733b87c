// The coupled tuning on the whole tree's linearisation (detail/coupled_tuning.h): on the authors'
// tree01 every branch plane's assigned mode ends within 1% of its frequency and damping ratio.
//
// Disabled: not met. Measured (2026-11-29, 4 segments): the per-chain calibration with the
// gravity floor (detail/gravity_floor.h) starts it stable (K + G positive definite), but its
// first Newton step on the log-stiffness makes one eigenvalue negative again (-0.97 (rad/s)^2),
// and it stops there: 76 planes > 5% off at the start, the worst 6.3x (the trunk's best mode
// holds 6% of its strain energy, heavy crowns share modes with their branches). Run with
// --gtest_also_run_disabled_tests to see the numbers.

#include <gtest/gtest.h>

#include "robots/authors_tree.h"
#include "simtree/robots/export_robot.h"
#include "test_util.h"

namespace simtree::robots {
namespace {

TEST(CoupledTuning, DISABLED_ConvergesOnAuthorsTree01) {
  const Tree tree = test::AuthorsTree01();
  ExportOptions options;
  options.calibration.coupled_iterations = 20;
  CalibrationReport report;
  MakeRobotModel(tree, options, "tree01", &report);
  EXPECT_TRUE(report.coupled);
  EXPECT_TRUE(report.coupled_converged)
      << "after " << report.coupled_iterations << " iterations: frequency off by "
      << report.worst_frequency_error << ", damping by " << report.worst_damping_error << ", "
      << report.groups_off << " planes > 5% off; lowest eigenvalue " << report.lowest_eigenvalue
      << ", " << report.unstable_modes
      << " below zero (gravity floor: " << report.gravity_stiffened_hinges
      << " hinges stiffened, K + G's lowest " << report.gravity_lowest_stiffness << ")";
  EXPECT_LT(report.worst_frequency_error, options.calibration.coupled_tolerance);
  EXPECT_LT(report.worst_damping_error, options.calibration.coupled_tolerance);
}

}  // namespace
}  // namespace simtree::robots
