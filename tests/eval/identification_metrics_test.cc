#include "simtree/eval/identification_metrics.h"

#include <cmath>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace simtree::eval {
namespace {

using ::testing::HasSubstr;

identification::LinkMaterial Link(int parent, int child, double f, double z,
                                  identification::EstimateStatus status) {
  identification::LinkMaterial l;
  l.parent = parent;
  l.child = child;
  l.label = fmt::format("M{}", child);
  l.value.status = status;
  if (status == identification::EstimateStatus::kOk) {
    l.value.frequency_hz = f;
    l.value.damping_ratio = z;
  }
  identification::ModalEstimate paper = l.value;
  if (status == identification::EstimateStatus::kOk) paper.damping_ratio = 2 * z;
  l.estimators = {{identification::EstimatorKind::kDampedSinusoidFit, l.value},
                  {identification::EstimatorKind::kHalfPowerFft, paper}};
  return l;
}

TEST(IdentificationMetrics, LinkErrorsAreRelativeAndMediansSkipWhatWasNotEstimated) {
  ModalTruth truth;
  truth.links = {{-1, 0, 1.0, 0.02}, {0, 1, 1.2, 0.03}, {1, 2, 1.5, 0.05}, {1, 3, 1.4, 0.04}};
  identification::MaterialsFile m;
  m.links = {Link(-1, 0, 1.01, 0.021, identification::EstimateStatus::kOk),
             Link(0, 1, 1.2, 0.027, identification::EstimateStatus::kOk),
             Link(1, 2, 0, 0, identification::EstimateStatus::kFlat),
             Link(1, 3, 1.428, 0.04, identification::EstimateStatus::kOk),
             Link(3, 9, 1.0, 0.03, identification::EstimateStatus::kOk)};
  const LinkScores s = ScoreLinks(m, truth);
  ASSERT_EQ(s.links.size(), 4u);
  EXPECT_EQ(s.summary.scored, 3);
  EXPECT_EQ(s.summary.not_estimated, 1);
  EXPECT_EQ(s.summary.no_truth, 1);
  EXPECT_NEAR(s.links[0].value.frequency_error, 0.01, 1e-12);
  EXPECT_NEAR(s.summary.median_frequency_error, 0.01, 1e-12);  // {0.01, 0, 0.02}
  EXPECT_NEAR(s.summary.median_damping_error, 0.05, 1e-12);    // {0.05, 0.1, 0}
  EXPECT_NEAR(s.summary.max_damping_error, 0.1, 1e-12);
  const LinkScores paper = ScoreLinks(m, truth, identification::EstimatorKind::kHalfPowerFft);
  EXPECT_NEAR(paper.summary.median_damping_error, 1.0, 1e-12);  // {1.1, 0.8, 1.0}
  EXPECT_THAT(FormatSummary("fit", s.summary), HasSubstr("1 not estimated"));
  EXPECT_THAT(FormatLinkScores(s), HasSubstr("| M1 | ok | 1.2000 |"));
}

TEST(IdentificationMetrics, ARunnerUpModeIsReportedAndTheNearestStrongModeScored) {
  ModalTruth truth;
  ModalTruth::Link two_modes{0, 1, 1.8, 0.02};
  two_modes.peaks = {{4, 1.8, 0.02, 0.01, 0.5}, {1, 1.0, 0.03, 0.02, 0.4}};
  truth.links = {two_modes, {0, 2, 1.2, 0.03}};
  identification::MaterialsFile m;
  m.links = {Link(0, 1, 1.01, 0.03, identification::EstimateStatus::kOk),
             Link(0, 2, 0, 0, identification::EstimateStatus::kFlat)};
  m.links[1].value.message = "no motion above the noise";
  const LinkScores s = ScoreLinks(m, truth);
  ASSERT_EQ(s.links.size(), 2u);
  // The runner-up (1.0 Hz) was found: far from the dominant, 1% from the runner-up.
  EXPECT_NEAR(s.links[0].value.frequency_error, 1 - 1.01 / 1.8, 1e-12);
  EXPECT_NEAR(s.links[0].nearest_mode_frequency_error, 0.01, 1e-12);
  EXPECT_NEAR(s.links[0].runner_up_ratio, 0.8, 1e-12);
  EXPECT_DOUBLE_EQ(s.links[0].runner_up_frequency_hz, 1.0);
  // No peaks listed, no estimate: nothing invented.
  EXPECT_EQ(s.links[1].runner_up_ratio, 0.0);
  EXPECT_TRUE(std::isnan(s.links[1].nearest_mode_frequency_error));
  EXPECT_EQ(s.links[1].message, "no motion above the noise");
}

// A chain of `count` vertical branches of 1 m.
Tree Chain(int count) {
  Tree tree;
  for (int b = 0; b < count; ++b) {
    Branch branch;
    branch.id = b;
    branch.parent = b - 1;
    branch.nodes = {{Eigen::Vector3d(0, 0, b), 0.1}, {Eigen::Vector3d(0, 0, b + 1), 0.1}};
    tree.branches.push_back(branch);
  }
  return tree;
}

TEST(IdentificationMetrics, OnlyTheTruthsOwnTreeIsScoredBranchByBranch) {
  const Tree truth = Chain(3);
  EXPECT_EQ(BranchMismatch(truth, truth), "");
  Tree nearly = truth;
  nearly.branches[2].nodes.back().position.x() += 0.005;  // within a centimetre
  EXPECT_EQ(BranchMismatch(nearly, truth), "");
  EXPECT_THAT(BranchMismatch(Chain(4), truth),
              HasSubstr("4 branches where the truth's tree has 3"));
  Tree renumbered = truth;
  std::swap(renumbered.branches[1].nodes, renumbered.branches[2].nodes);
  EXPECT_THAT(BranchMismatch(renumbered, truth), HasSubstr("branch 1 lies 1.000 m"));
}

TEST(IdentificationMetrics, BranchesAreScoredByTheirSource) {
  Tree tree = Chain(3);
  for (int b = 0; b < 3; ++b) {
    Branch& branch = tree.branches[b];
    Material m;
    m.modes[2].frequency_hz = 1.0 + 0.1 * b;
    m.modes[2].damping_ratio = 0.03;
    m.source = b == 0 ? MaterialSource::kMeasured : MaterialSource::kInterpolated;
    branch.material = m;
  }
  ModalTruth truth;
  truth.branches = {{0, 1.0, 0.03}, {1, 1.0, 0.03}, {2, 1.0, 0.03}};
  const BranchScores s = ScoreBranches(tree, truth);
  EXPECT_EQ(s.measured.scored, 1);
  EXPECT_EQ(s.interpolated.scored, 2);
  EXPECT_NEAR(s.interpolated.median_frequency_error, 0.15, 1e-12);
  EXPECT_NEAR(s.measured.median_frequency_error, 0.0, 1e-12);
}

}  // namespace
}  // namespace simtree::eval
