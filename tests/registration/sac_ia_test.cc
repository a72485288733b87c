#include "simtree/registration/detail/sac_ia.h"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include <open3d/pipelines/registration/Feature.h>
#include "preprocessing/option_fixtures.h"

namespace simtree::registration {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

double RotationDeg(const Eigen::Isometry3d& t) {
  return std::abs(Eigen::AngleAxisd(t.linear()).angle()) / kDeg;
}

// A skeleton-like point set: a trunk and a few curved limbs, points 2 cm apart.
open3d::geometry::PointCloud BranchyPoints(uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  open3d::geometry::PointCloud cloud;
  for (double z = 0; z < 0.8; z += 0.02) cloud.points_.emplace_back(0, 0, z);
  for (int limb = 0; limb < 5; ++limb) {
    Eigen::Vector3d p(0, 0, 0.3 + 0.1 * limb);
    Eigen::Vector3d d = Eigen::Vector3d(u(rng), u(rng), 0.8 + 0.3 * u(rng)).normalized();
    for (int k = 0; k < 25; ++k) {
      p += 0.02 * d;
      d = (d + 0.15 * Eigen::Vector3d(u(rng), u(rng), u(rng))).normalized();
      cloud.points_.push_back(p);
    }
  }
  return cloud;
}

std::shared_ptr<open3d::pipelines::registration::Feature> Features(
    open3d::geometry::PointCloud& cloud, const Eigen::Vector3d& up) {
  cloud.EstimateNormals(open3d::geometry::KDTreeSearchParamHybrid(0.06, 30));
  cloud.OrientNormalsToAlignWithDirection(up);
  return open3d::pipelines::registration::ComputeFPFHFeature(
      cloud, open3d::geometry::KDTreeSearchParamHybrid(0.16, 100));
}

Eigen::Isometry3d Motion(double yaw_deg) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = (Eigen::AngleAxisd(yaw_deg * kDeg, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(4 * kDeg, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  t.translation() = Eigen::Vector3d(0.4, -0.2, 0.1);
  return t;
}

TEST(FitRigid, RecoversAKnownMotion) {
  const auto cloud = BranchyPoints(1);
  const Eigen::Isometry3d truth = Motion(130);
  std::vector<Eigen::Vector3d> from = cloud.points_, to;
  for (const auto& p : from) to.push_back(truth * p);
  const Eigen::Isometry3d fitted = FitRigid(from, to);
  EXPECT_LT((fitted.matrix() - truth.matrix()).norm(), 1e-9);
  // With the up directions given, only the turn about up is fitted, and it is exact too.
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Eigen::Isometry3d constrained = FitRigid(from, to, up, truth.linear() * up);
  EXPECT_LT((constrained.matrix() - truth.matrix()).norm(), 1e-9);
}

TEST(SampleConsensus, AlignsSkeletonsByTheirFeatures) {
  auto source = BranchyPoints(2);
  const Eigen::Isometry3d truth = Motion(150);
  open3d::geometry::PointCloud target = source;
  target.Transform(truth.matrix());
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0, 0.003);
  for (auto& p : target.points_) p += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const auto source_features = Features(source, up);
  const auto target_features = Features(target, truth.linear() * up);

  SacIaPrior prior;
  prior.source_up = up;
  prior.target_up = truth.linear() * up;
  const CoarseAlignment with_up =
      SampleConsensusInitialAlignment(source, *source_features, target, *target_features, prior);
  ASSERT_TRUE(with_up.found);
  EXPECT_LT(RotationDeg(with_up.target_from_source.inverse() * truth), 1.0);
  EXPECT_LT((with_up.target_from_source.translation() - truth.translation()).norm(), 0.01);
  EXPECT_GT(with_up.inlier_share, 0.9);

  // The paper's SAC-IA, without priors, on the same clean points.
  const CoarseAlignment plain =
      SampleConsensusInitialAlignment(source, *source_features, target, *target_features, {});
  ASSERT_TRUE(plain.found);
  EXPECT_LT(RotationDeg(plain.target_from_source.inverse() * truth), 2.0);
}

TEST(SampleConsensus, CentrePriorRefusesFarHypotheses) {
  auto source = BranchyPoints(4);
  const Eigen::Isometry3d truth = Motion(60);
  open3d::geometry::PointCloud target = source;
  target.Transform(truth.matrix());
  const auto sf = Features(source, Eigen::Vector3d::UnitZ());
  const auto tf = Features(target, truth.linear() * Eigen::Vector3d::UnitZ());
  SacIaPrior prior;
  // A centre prior that no hypothesis can meet: the target centre 5 m off.
  prior.source_center = Eigen::Vector3d::Zero();
  prior.target_center = Eigen::Vector3d(5, 0, 0);
  prior.max_center_offset_m = 0.2;
  const CoarseAlignment none = SampleConsensusInitialAlignment(source, *sf, target, *tf, prior);
  EXPECT_FALSE(none.found);
  EXPECT_EQ(none.hypotheses, 0);
}

TEST(SampleConsensus, TooFewPointsFindNothing) {
  open3d::geometry::PointCloud tiny;
  tiny.points_ = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.1, 0, 0)};
  open3d::pipelines::registration::Feature f;
  f.Resize(33, 2);
  EXPECT_FALSE(SampleConsensusInitialAlignment(tiny, f, tiny, f, {}).found);
}

TEST(SampleConsensus, NonsenseOptionsAreRefused) {
  using test::RefusedField;
  EXPECT_EQ(RefusedField(SacIaOptions{}), "");
  EXPECT_EQ(RefusedField(SacIaOptions{.samples = 1}), "samples");
  EXPECT_EQ(RefusedField(SacIaOptions{.inlier_distance_m = 0}), "inlier_distance_m");
  EXPECT_EQ(RefusedField(SacIaOptions{.edge_length_similarity = 1.2}), "edge_length_similarity");
}

}  // namespace
}  // namespace simtree::registration
