// The coupled tuning on the whole tree's linearisation (detail/coupled_tuning.h): on the authors'
// tree01 every branch plane's assigned mode ends within 1% of its frequency and damping ratio.
//
// Disabled: not met. Measured (2026-11-29, 4 segments): with the per-chain calibration (gravity
// counted per chain) the whole tree's linearisation has one eigenvalue below zero (-0.68
// (rad/s)^2: the free tree is slowly unstable under gravity), so the tuning stops before its
// first step. Without gravity in the chains it had three (down to -22), and once stiffened
// out of them the Newton steps on the log-stiffness diverged (worst plane 4.3x off at the
// start: the trunk's best mode holds 6% of its strain energy, heavy crowns share modes with
// their branches). Run with --gtest_also_run_disabled_tests to see the numbers.

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
      << ", " << report.unstable_modes << " below zero";
  EXPECT_LT(report.worst_frequency_error, options.calibration.coupled_tolerance);
  EXPECT_LT(report.worst_damping_error, options.calibration.coupled_tolerance);
}

}  // namespace
}  // namespace simtree::robots
