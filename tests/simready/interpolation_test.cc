#include "simtree/simready/detail/interpolation.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "identification/tree_fixture.h"

namespace simtree::simready {
namespace {

using ::testing::HasSubstr;

double Cantilever(const Branch& b, double c) {
  return c * b.base().radius / std::pow(b.Length(), 2);
}

TEST(Interpolation, BranchesThatFollowTheCantileverLawAreFittedByIt) {
  const Tree tree = test::IdentificationTree();
  std::vector<BranchSample> samples;
  for (int b : {0, 1, 2, 4, 5}) samples.push_back({b, Cantilever(tree.branches[b], 40.0), 0.03});
  const InterpolationModel model = FitInterpolationModel(tree, samples);
  EXPECT_EQ(model.kind, FrequencyModelKind::kCantilever) << model.Describe();
  EXPECT_NEAR(model.coefficients[1], 1.0, 1e-9);
  EXPECT_NEAR(model.leave_one_out_log_error, 0.0, 1e-9);
  // Branch 3 lies inside the measured range: predicted exactly.
  const Branch& b3 = tree.branches[3];
  const double truth = Cantilever(b3, 40.0);
  ASSERT_GT(truth, model.min_frequency_hz);
  ASSERT_LT(truth, model.max_frequency_hz);
  EXPECT_NEAR(model.Frequency(b3.base().radius, b3.Length()), truth, 1e-9 * truth);
  // Outside the measured range predictions are clamped to it.
  EXPECT_DOUBLE_EQ(model.Frequency(0.5, 0.1), model.max_frequency_hz);
  EXPECT_DOUBLE_EQ(model.Frequency(0.001, 10.0), model.min_frequency_hz);
  EXPECT_THAT(model.Describe(), HasSubstr("log(r/L^2)"));
}

TEST(Interpolation, BranchesThatAllSwingTogetherGiveTheirMedian) {
  const Tree tree = test::IdentificationTree();
  // Siblings on the trunk: no one hangs from another, so the ancestor model ties with the median
  // and the simpler one is kept.
  const std::vector<BranchSample> samples = {{1, 1.10, 0.03}, {2, 1.12, 0.04}, {3, 1.09, 0.05}};
  const InterpolationModel model = FitInterpolationModel(tree, samples);
  EXPECT_EQ(model.kind, FrequencyModelKind::kMedian) << model.Describe();
  EXPECT_NEAR(model.Frequency(0.01, 0.3), 1.10, 1e-9);
  EXPECT_NEAR(model.Frequency(tree, 4), 1.10, 1e-9);
}

// A pull test's modes live in subtrees: the pulled branch 1 and the branch 4 hanging from it
// swing at its own 2 Hz, the trunk and the rest of the tree at 1 Hz, whatever their size. The
// nearest measured ancestor predicts the branches of each subtree; the size laws cannot.
TEST(Interpolation, BranchesThatSwingWithTheirSubtreeTakeTheirMeasuredAncestors) {
  const Tree tree = test::IdentificationTree();  // 1, 2, 3 on the trunk 0; 4 on 1; 5 on 2
  const InterpolationModel model = FitInterpolationModel(
      tree, {{0, 1.0, 0.03}, {1, 2.0, 0.03}, {4, 2.0, 0.03}, {2, 1.0, 0.03}, {5, 1.0, 0.03}});
  EXPECT_EQ(model.kind, FrequencyModelKind::kNearestMeasuredAncestor) << model.Describe();
  EXPECT_THAT(model.Describe(), HasSubstr("nearest measured ancestor"));
  EXPECT_DOUBLE_EQ(model.Frequency(tree, 3), 1.0);   // hangs from the trunk
  EXPECT_DOUBLE_EQ(model.Frequency(tree, 4), 2.0);   // from branch 1
  EXPECT_DOUBLE_EQ(model.Frequency(tree, 0), 1.0);   // no ancestor: the median
  EXPECT_DOUBLE_EQ(model.Frequency(0.5, 0.1), 1.0);  // no place in the tree: the median
  EXPECT_THROW(model.Frequency(tree, 6), InputError);
}

TEST(Interpolation, DampingByLevelElseTheNearestLevel) {
  const Tree tree = test::IdentificationTree();  // levels: 0; 1, 1, 1; 2, 2
  const InterpolationModel model =
      FitInterpolationModel(tree, {{0, 1.0, 0.02}, {1, 1.2, 0.04}, {2, 1.3, 0.06}});
  EXPECT_DOUBLE_EQ(model.Damping(0), 0.02);
  EXPECT_DOUBLE_EQ(model.Damping(1), 0.05);
  EXPECT_DOUBLE_EQ(model.Damping(2), 0.05);  // nothing on level 2: level 1's
  EXPECT_DOUBLE_EQ(model.Damping(7), 0.05);
  const InterpolationModel one = FitInterpolationModel(tree, {{4, 1.4, 0.03}});
  EXPECT_DOUBLE_EQ(one.Damping(0), 0.03);
  EXPECT_DOUBLE_EQ(one.Frequency(0.05, 1.0), 1.4);
}

TEST(Interpolation, NothingMeasuredOrAnUnknownBranchIsAnError) {
  const Tree tree = test::IdentificationTree();
  EXPECT_THROW(FitInterpolationModel(tree, {}), InputError);
  try {
    FitInterpolationModel(tree, {{42, 1.0, 0.03}});
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("branch 42"));
    EXPECT_THAT(e.what(), HasSubstr("6 branches"));
  }
}

}  // namespace
}  // namespace simtree::simready
