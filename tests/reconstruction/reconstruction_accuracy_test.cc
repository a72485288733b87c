// Long checks (label slow): stand-in Kinect scans of the authors' demo trees scored against them,
// and the five real laser scans reconstructed into complete trees that fit their points (the tall
// ITSMe trees with their trunk base measured like TreeQSM's).

#include <utility>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "reconstruction/standin_scan.h"
#include "simtree/core/tree_file.h"
#include "simtree/core/validate.h"
#include "simtree/eval/reconstruction_metrics.h"
#include "simtree/io/point_cloud_io.h"
#include "simtree/reconstruction/reconstruct.h"
#include "test_util.h"

namespace simtree::reconstruction {
namespace {

class AuthorsTree : public ::testing::TestWithParam<std::tuple<const char*, double>> {};

TEST_P(AuthorsTree, StandInScanMeetsTheIssueTargets) {
  const auto [name, noise_mm] = GetParam();
  const Tree truth =
      ReadTreeFile(test::SharedData(std::string("authors-demo/tree_model/") + name + ".txt"));
  test::StandInScanOptions options;
  options.noise_at_2m_m = noise_mm * 1e-3;
  const auto scan = test::ScanLikeAKinect(truth, options);
  const ReconstructionResult r = ReconstructTree(scan.points, name);
  const eval::TruthScores s = eval::ScoreAgainstTruth(r.tree, truth);
  EXPECT_GE(s.recall, 0.9) << eval::FormatTruthScores(s);
  EXPECT_GE(s.precision, 0.9) << eval::FormatTruthScores(s);
  EXPECT_LE(s.mean_skeleton_distance_m, 0.015) << eval::FormatTruthScores(s);
  EXPECT_LE(s.trunk_radius_error, 0.1) << eval::FormatTruthScores(s);
}

INSTANTIATE_TEST_SUITE_P(Noise, AuthorsTree,
                         ::testing::Combine(::testing::Values("tree01", "tree02"),
                                            ::testing::Values(2.0, 3.0)));

// A real scan and the share of its points the model must hold within 2 cm: a few points below
// what the defaults reach (docs/benchmarks.md), so a step that loses twigs fails here.
struct RealScanCase {
  const char* name;
  double min_share_within;
};
class RealScan : public ::testing::TestWithParam<RealScanCase> {};

TEST_P(RealScan, ReconstructsACompleteConnectedTreeThatFitsThePoints) {
  const auto [name, min_share_within] = GetParam();
  const auto cloud = ReadPointCloud(test::SharedData(std::string("real-scans/") + name));
  const ReconstructionResult r = ReconstructTree(cloud.points_, name);
  EXPECT_TRUE(FindProblems(r.tree).empty());
  ASSERT_TRUE(r.trunk.found) << r.trunk.note;
  // Connected by construction (every branch hangs on its parent); complete: most points are near
  // the model, and the tree has a real hierarchy.
  const eval::CloudFitScores fit = eval::ScoreAgainstCloud(r.tree, cloud.points_);
  EXPECT_GE(fit.share_within, min_share_within) << eval::FormatCloudFit(fit);
  EXPECT_LE(fit.median_distance_m, 0.03) << eval::FormatCloudFit(fit);
  EXPECT_GE(fit.branches, 30) << eval::FormatCloudFit(fit);
  ASSERT_GE(fit.branches_by_level.size(), 3u);
  EXPECT_LE(r.unreached_points, r.working_points / 5);
}

INSTANTIATE_TEST_SUITE_P(Scans, RealScan,
                         ::testing::Values(RealScanCase{"tree1.xyz", 0.63},
                                           RealScanCase{"tree7.xyz", 0.80},
                                           RealScanCase{"rtwig_cloud.xyz", 0.98},
                                           RealScanCase{"itsme_tree1.xyz", 0.53},
                                           RealScanCase{"itsme_tree2.xyz", 0.65}));

// The tall ITSMe trees: the trunk's base radius within 15% of TreeQSM's (real-scans/README.md).
class TallScan : public ::testing::TestWithParam<std::pair<const char*, double>> {};

TEST_P(TallScan, MeasuresTheTrunkBaseLikeTreeQsm) {
  const auto [name, treeqsm_base_radius] = GetParam();
  const auto cloud = ReadPointCloud(test::SharedData(std::string("real-scans/") + name));
  const ReconstructionResult r = ReconstructTree(cloud.points_, name);
  ASSERT_TRUE(r.trunk.found) << r.trunk.note;
  EXPECT_NEAR(r.tree.trunk().nodes.front().radius, treeqsm_base_radius, 0.15 * treeqsm_base_radius)
      << r.trunk.note;
}

INSTANTIATE_TEST_SUITE_P(Itsme, TallScan,
                         ::testing::Values(std::pair<const char*, double>{"itsme_tree1.xyz", 0.087},
                                           std::pair<const char*, double>{"itsme_tree2.xyz",
                                                                          0.156}));

}  // namespace
}  // namespace simtree::reconstruction
