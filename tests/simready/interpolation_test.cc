#include "simtree/simready/detail/interpolation.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "identification/tree_fixture.h"
#include "simtree/core/error.h"
#include "simtree/core/units.h"
#include "simtree/simready/detail/sample_weights.h"

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

namespace simtree::simready {
namespace {

TEST(SampleWeights, InverseVarianceFlooredAtTheMedianDeviation) {
  // Relative sds 0.5%, 2%, 4%; not given; infinite. The floor is their median, 2%.
  const std::vector<double> w =
      InverseVarianceWeights({1.0, 2.0, 1.0, 1.0, 1.0},
                             {0.005, 0.04, 0.04, kNaN, std::numeric_limits<double>::infinity()});
  EXPECT_DOUBLE_EQ(w[0], 1.0);   // under the floor: the floor's weight
  EXPECT_DOUBLE_EQ(w[1], 1.0);   // 0.04 of 2.0 is 2%
  EXPECT_DOUBLE_EQ(w[2], 0.25);  // twice the floor's sd: a quarter
  EXPECT_DOUBLE_EQ(w[3], 1.0);   // none given: a typical value
  EXPECT_DOUBLE_EQ(w[4], 0.25);  // infinite: the least certain given
  const std::vector<double> none = InverseVarianceWeights({1.0, 2.0}, {kNaN, kNaN});
  EXPECT_EQ(none, std::vector<double>({1.0, 1.0}));
}

TEST(SampleWeights, WeightedMedianMatchesTheMedianForEqualWeights) {
  EXPECT_DOUBLE_EQ(WeightedMedian({3, 1, 2}, {1, 1, 1}), 2.0);
  EXPECT_DOUBLE_EQ(WeightedMedian({4, 1, 3, 2}, {1, 1, 1, 1}), 2.5);
  EXPECT_DOUBLE_EQ(WeightedMedian({1, 2, 3}, {0.1, 0.1, 1}), 3.0);
  EXPECT_TRUE(std::isnan(WeightedMedian({}, {})));
}

// The cantilever law on five branches known to 1%, and branch 3 read at twice its law with a 50%
// deviation: the weighted fit follows the five, the unweighted one is pulled.
TEST(Interpolation, WeightsByInverseVarianceFollowTheCertainBranches) {
  const Tree tree = test::IdentificationTree();
  std::vector<BranchSample> samples;
  for (int b : {0, 1, 2, 4, 5}) {
    const double f = Cantilever(tree.branches[b], 40.0);
    samples.push_back({b, f, 0.03, 0.01 * f, 0.003});
  }
  const double law3 = Cantilever(tree.branches[3], 40.0);
  samples.push_back({3, 2 * law3, 0.09, law3, 0.045});
  InterpolationOptions weighted;
  weighted.weight_by_uncertainty = true;
  weighted.clamp_to_measured = false;
  InterpolationOptions plain = weighted;
  plain.weight_by_uncertainty = false;
  const InterpolationModel w = FitInterpolationModel(tree, samples, weighted);
  const InterpolationModel p = FitInterpolationModel(tree, samples, plain);
  EXPECT_TRUE(w.weighted);
  EXPECT_THAT(w.Describe(), HasSubstr("weighted by 1/sd^2"));
  const Branch& b3 = tree.branches[3];
  const double wf = w.Frequency(b3.base().radius, b3.Length());
  const double pf = p.Frequency(b3.base().radius, b3.Length());
  EXPECT_NEAR(wf / law3, 1.0, 0.01) << w.Describe();
  EXPECT_GT(std::abs(pf / law3 - 1), 0.05) << p.Describe();
  // Damping: branch 3's 0.09 (level 1, sd half its value) weighs 1/25 of the others'.
  EXPECT_DOUBLE_EQ(w.Damping(1), 0.03);
}

}  // namespace
}  // namespace simtree::simready
