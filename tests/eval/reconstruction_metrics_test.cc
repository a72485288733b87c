#include "simtree/eval/reconstruction_metrics.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/core/frames.h"

namespace simtree::eval {
namespace {

// A trunk (1.5 m, radius 8 cm to 4 cm) with three side branches of 3 cm, 1.5 cm and 0.5 cm.
Tree Truth() {
  Tree tree;
  auto add = [&](int parent, int parent_node, Eigen::Vector3d base, Eigen::Vector3d dir,
                 double length, double r0, double r1) {
    Branch b;
    b.id = tree.size();
    b.parent = parent;
    b.parent_node = parent_node;
    for (int i = 0; i <= 10; ++i) {
      b.nodes.push_back({base + dir.normalized() * length * i / 10, r0 + (r1 - r0) * i / 10});
    }
    tree.branches.push_back(b);
  };
  add(-1, 0, {0, 0, 0}, {0, 0, 1}, 1.5, 0.08, 0.04);
  add(0, 4, tree.branches[0].nodes[4].position, {1, 0, 1}, 0.8, 0.03, 0.01);
  add(0, 6, tree.branches[0].nodes[6].position, {-1, 0.5, 1}, 0.6, 0.015, 0.005);
  add(0, 8, tree.branches[0].nodes[8].position, {0, -1, 1}, 0.4, 0.005, 0.002);
  AssignLevels(tree);
  ComputeFrames(tree);
  return tree;
}

Tree Shifted(Tree tree, const Eigen::Vector3d& by) {
  for (Branch& b : tree.branches) {
    for (Node& n : b.nodes) n.position += by;
  }
  return tree;
}

TEST(ReconstructionMetrics, ATreeAgainstItselfIsPerfect) {
  const TruthScores s = ScoreAgainstTruth(Truth(), Truth());
  EXPECT_EQ(s.true_branches, 3);  // the 5 mm branch is not scored
  EXPECT_DOUBLE_EQ(s.recall, 1.0);
  EXPECT_EQ(s.reconstructed_branches, 3);
  EXPECT_DOUBLE_EQ(s.precision, 1.0);
  EXPECT_NEAR(s.mean_skeleton_distance_m, 0.0, 1e-9);
  EXPECT_NEAR(s.radius_error, 0.0, 1e-9);
  EXPECT_NEAR(s.trunk_radius_error, 0.0, 1e-9);
  EXPECT_NEAR(s.length_error, 0.0, 1e-9);
  EXPECT_GT(s.true_length_m, 2.5);
  EXPECT_LT(s.true_length_m, Truth().branches[0].Length() + 1.5);
}

TEST(ReconstructionMetrics, AShiftIsTheSkeletonDistanceAndAFarShiftLosesEverything) {
  const TruthScores near = ScoreAgainstTruth(Shifted(Truth(), {0.01, 0, 0}), Truth());
  // 1 cm across the trunk, less across the branches that lean along x.
  EXPECT_LE(near.mean_skeleton_distance_m, 0.0101);
  EXPECT_GE(near.mean_skeleton_distance_m, 0.007);
  EXPECT_DOUBLE_EQ(near.recall, 1.0);
  const TruthScores far = ScoreAgainstTruth(Shifted(Truth(), {0.5, 0, 0}), Truth());
  EXPECT_DOUBLE_EQ(far.recall, 0.0);
  EXPECT_DOUBLE_EQ(far.precision, 0.0);
}

TEST(ReconstructionMetrics, AMissingBranchLowersRecallAndAWrongOnePrecision) {
  Tree missing = Truth();
  missing.branches.pop_back();
  missing.branches.pop_back();  // drops the 1.5 cm and the 5 mm branch
  const TruthScores m = ScoreAgainstTruth(missing, Truth());
  EXPECT_EQ(m.found, 2);
  EXPECT_NEAR(m.recall, 2.0 / 3.0, 1e-9);
  EXPECT_DOUBLE_EQ(m.precision, 1.0);
  EXPECT_LT(m.length_error, -0.05);

  Tree extra = Truth();
  Branch wrong = extra.branches[1];
  wrong.id = extra.size();
  for (Node& n : wrong.nodes) n.position.y() += 0.3 * (n.position.z() - 0.6);  // veers away
  extra.branches.push_back(wrong);
  AssignLevels(extra);
  const TruthScores e = ScoreAgainstTruth(extra, Truth());
  EXPECT_DOUBLE_EQ(e.recall, 1.0);
  EXPECT_EQ(e.reconstructed_branches, 4);
  EXPECT_NEAR(e.precision, 0.75, 1e-9);
  EXPECT_GT(e.length_error, 0.1);
}

TEST(ReconstructionMetrics, ATwigAlongThinWoodClaimsNoThickLengthWhereItLeavesTheTrunk) {
  // The 5 mm branch found, but leaving the trunk 10 cm lower and running up along its bark
  // first: its start lies near the thick trunk, yet the twig follows thin true wood.
  Tree found = Truth();
  Branch& twig = found.branches[3];
  const Eigen::Vector3d start = found.branches[0].nodes[8].position;
  twig.nodes.insert(twig.nodes.begin(), {start + Eigen::Vector3d(0, -0.06, -0.1), 0.005});
  twig.nodes.insert(twig.nodes.begin(), {start + Eigen::Vector3d(0, 0, -0.1), 0.005});
  const TruthScores s = ScoreAgainstTruth(found, Truth());
  EXPECT_NEAR(s.length_error, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(s.precision, 1.0);
}

TEST(ReconstructionMetrics, RadiusAndTrunkErrorsAreRelative) {
  Tree fat = Truth();
  for (Branch& b : fat.branches) {
    for (Node& n : b.nodes) n.radius *= 1.2;
  }
  const TruthScores s = ScoreAgainstTruth(fat, Truth());
  EXPECT_NEAR(s.radius_error, 0.2, 1e-6);
  EXPECT_NEAR(s.trunk_radius_error, 0.2, 1e-6);
}

TEST(ReconstructionMetrics, SurfaceDistanceOfPointsAroundABranch) {
  const Tree tree = Truth();
  // On the trunk's surface, 1 cm outside it, 1.5 cm inside it, and far away.
  const double r = 0.08 - 0.04 * 0.5 / 1.5;  // trunk radius at z = 0.5
  const std::vector<Eigen::Vector3d> points = {
      {0, r, 0.5}, {0, r + 0.01, 0.5}, {0, r - 0.015, 0.5}, {3, 0, 0.5}};
  const auto d = SurfaceDistances(tree, points);
  EXPECT_NEAR(d[0], 0.0, 1e-3);
  EXPECT_NEAR(d[1], 0.01, 1e-3);
  EXPECT_NEAR(d[2], 0.015, 1e-3);
  EXPECT_GT(d[3], 2.5);
  const CloudFitScores fit = ScoreAgainstCloud(tree, points);
  EXPECT_EQ(fit.points, 4u);
  EXPECT_DOUBLE_EQ(fit.share_within, 0.75);
  EXPECT_EQ(fit.branches, 4);
  EXPECT_THAT(fit.branches_by_level, ::testing::ElementsAre(1, 3));
  EXPECT_THAT(FormatCloudFit(fit), ::testing::HasSubstr("75.0% within 2 cm"));
}

TEST(ReconstructionMetrics, EmptyTreesScoreZeroWithoutCrashing) {
  const TruthScores s = ScoreAgainstTruth(Tree{}, Truth());
  EXPECT_EQ(s.recall, 0.0);
  const CloudFitScores fit = ScoreAgainstCloud(Tree{}, std::vector<Eigen::Vector3d>{{0, 0, 0}});
  EXPECT_EQ(fit.branches, 0);
}

TEST(ReconstructionMetrics, NonsenseOptionsAreRefusedByName) {
  EXPECT_THROW(
      {
        try {
          ScoreAgainstTruth(Truth(), Truth(), {.found_share = 1.5});
        } catch (const InputError& e) {
          EXPECT_STREQ(e.what(), "options: found_share: expected a value in [0, 1], got 1.5");
          throw;
        }
      },
      InputError);
  EXPECT_THROW(ScoreAgainstTruth(Truth(), Truth(), {.sample_step_m = 0.0}), InputError);
}

TEST(ReconstructionMetrics, MissedThinEndsCountOnlyInTheFullSkeletonDistance) {
  const Tree truth = Truth();
  Tree reconstruction = truth;
  // Branch 2 tapers from 1.5 to 0.5 cm: drop its end thinner than 1 cm (what a camera misses).
  reconstruction.branches[2].nodes.resize(5);
  const TruthScores scores = ScoreAgainstTruth(reconstruction, truth);
  EXPECT_LT(scores.thick_skeleton_distance_m, 0.001);
  EXPECT_GT(scores.mean_skeleton_distance_m, 0.002);
}

}  // namespace
}  // namespace simtree::eval
