#include "simtree/pipeline/detail/branch_stiffness.h"

#include <gtest/gtest.h>

#include "pipeline/pulled_scenes.h"
#include "simtree/core/error.h"

using namespace simtree;
using simtree::test::ReleasedScene;
using simtree::test::Scene;

namespace {

// Branches twice as high in frequency as identified: the calibration finds the factor from the
// tracked pull, and the tree as identified replays it worse.
TEST(CalibrateBranchStiffness, FindsHowMuchStifferTheBranchesAre) {
  const Eigen::Vector3d force(0, 30, -40);
  const double arc = (0.2 + 0.75 * 2.5 / 6) * 1.5;
  const Scene s = ReleasedScene(force, arc, 3.0, 2.0);
  pipeline::detail::StiffnessCalibrationOptions options;
  options.factors = {1.0, 1.41, 2.0, 2.83};
  const pipeline::detail::StiffnessCalibration c = pipeline::detail::CalibrateBranchStiffness(
      s.tree, s.tracks, s.world_from_camera, 3.0, {}, {}, options);
  EXPECT_DOUBLE_EQ(c.factor, 2.0);
  ASSERT_EQ(c.trials.size(), 4u);
  EXPECT_GT(c.trials[0].residual_rms_m, 3 * c.trials[2].residual_rms_m);
  EXPECT_NEAR(c.fit.motion.release_s, 3.0, 0.005);
  EXPECT_LT((c.fit.force - force).norm(), 0.05 * force.norm()) << c.fit.force.transpose();
  options.factors = {2.0, 1.0};
  EXPECT_THROW(options.Validate(), InputError);
}

TEST(StiffenBranches, ScalesEveryBranchAboveTheTrunk) {
  const Tree tree = test::ThreeLevelTree();
  const Tree stiff = pipeline::detail::StiffenBranches(tree, 2.0);
  EXPECT_DOUBLE_EQ(stiff.branches[0].material->modes[0].frequency_hz,
                   tree.branches[0].material->modes[0].frequency_hz);
  for (int b = 1; b < 4; ++b) {
    EXPECT_DOUBLE_EQ(stiff.branches[b].material->modes[0].frequency_hz,
                     2.0 * tree.branches[b].material->modes[0].frequency_hz);
    EXPECT_DOUBLE_EQ(stiff.branches[b].material->stiffness,
                     4.0 * tree.branches[b].material->stiffness);
    EXPECT_DOUBLE_EQ(stiff.branches[b].material->mass_kg, tree.branches[b].material->mass_kg);
  }
}

}  // namespace
