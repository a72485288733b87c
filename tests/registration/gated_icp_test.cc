#include "simtree/registration/detail/gated_icp.h"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "preprocessing/option_fixtures.h"

namespace simtree::registration {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A bumpy sheet z = 2 + 0.05 sin(4x) cos(3y) with normals towards the camera (-z side).
open3d::geometry::PointCloud Sheet(double spacing, double z0 = 2.0, bool towards_camera = true) {
  open3d::geometry::PointCloud cloud;
  for (double x = -0.6; x <= 0.6; x += spacing) {
    for (double y = -0.6; y <= 0.6; y += spacing) {
      cloud.points_.emplace_back(x, y, z0 + 0.05 * std::sin(4 * x) * std::cos(3 * y));
    }
  }
  cloud.EstimateNormals(open3d::geometry::KDTreeSearchParamHybrid(4 * spacing, 30));
  cloud.OrientNormalsTowardsCameraLocation(towards_camera ? Eigen::Vector3d::Zero()
                                                          : Eigen::Vector3d(0, 0, 10));
  return cloud;
}

Eigen::Isometry3d SmallMotion() {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() =
      Eigen::AngleAxisd(1.5 * kDeg, Eigen::Vector3d(0.3, 1, 0.2).normalized()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(0.02, -0.015, 0.01);
  return t;
}

TEST(GatedIcp, RecoversASmallMotion) {
  const auto target = Sheet(0.01);
  auto source = target;
  const Eigen::Isometry3d truth = SmallMotion();
  source.Transform(truth.inverse().matrix());  // target = truth * source
  const open3d::geometry::KDTreeFlann tree(target);
  GatedIcpOptions options;
  options.max_distances_m = {0.06, 0.03, 0.015};
  options.iterations_per_stage = 30;
  const IcpResult r =
      GatedPointToPlaneIcp(source, target, tree, Eigen::Isometry3d::Identity(), options);
  EXPECT_LT((r.target_from_source.matrix() - truth.matrix()).norm(), 2e-3);
  EXPECT_GT(r.fitness, 0.95);
  EXPECT_LT(r.rmse_m, 0.002);
}

TEST(GatedIcp, TheNormalGateKeepsAFrontOffItsBack) {
  // The front of a thin plate seen from one side and its back seen from the other, 1 cm behind:
  // normals opposite. Plain ICP pulls them together (the bias NOTES.md measured at 180 degrees);
  // the gate refuses every such pair, so nothing moves.
  const auto front = Sheet(0.01, 2.0, true);
  const auto back = Sheet(0.01, 2.01, false);
  const open3d::geometry::KDTreeFlann tree(back);
  GatedIcpOptions gated;
  gated.max_distances_m = {0.03, 0.015};
  const IcpResult kept =
      GatedPointToPlaneIcp(front, back, tree, Eigen::Isometry3d::Identity(), gated);
  EXPECT_LT(kept.target_from_source.translation().norm(), 1e-9);
  EXPECT_EQ(kept.correspondences, 0);
  GatedIcpOptions plain = gated;
  plain.max_normal_angle_deg = 180.0;
  const IcpResult pulled =
      GatedPointToPlaneIcp(front, back, tree, Eigen::Isometry3d::Identity(), plain);
  EXPECT_NEAR(pulled.target_from_source.translation().z(), 0.01, 0.002);
}

// The halves of three branches (cylinders) facing a camera at `camera`, with their true normals.
open3d::geometry::PointCloud BranchShells(const Eigen::Vector3d& camera) {
  struct Branch {
    Eigen::Vector3d centre, axis;
    double radius;
  };
  const Branch branches[] = {
      {Eigen::Vector3d(0, 0, 3), Eigen::Vector3d(0, 1, 0), 0.08},
      {Eigen::Vector3d(0.3, -0.4, 3), Eigen::Vector3d(1, 1, 0.3), 0.04},
      {Eigen::Vector3d(-0.3, -0.5, 3.1), Eigen::Vector3d(-1, 1, -0.4), 0.03}};
  open3d::geometry::PointCloud cloud;
  for (const Branch& b : branches) {
    const Eigen::Vector3d a = b.axis.normalized();
    const Eigen::Vector3d e1 = a.unitOrthogonal(), e2 = a.cross(e1);
    for (double t = -0.4; t <= 0.4; t += 0.005) {
      for (double angle = 0; angle < 2 * std::numbers::pi; angle += 0.005 / b.radius) {
        const Eigen::Vector3d n = std::cos(angle) * e1 + std::sin(angle) * e2;
        const Eigen::Vector3d p = b.centre + t * a + b.radius * n;
        // Seen when facing the camera, grazing sides (beyond 75 deg) dropped as a sensor does.
        if (n.dot((camera - p).normalized()) < std::cos(75 * kDeg)) continue;
        cloud.points_.push_back(p);
        cloud.normals_.push_back(n);
      }
    }
  }
  return cloud;
}

TEST(GatedIcp, SymmetricObjectiveDoesNotPullOneSidedShellsTogether) {
  // Branches seen from two cameras 144 degrees apart about them, started at the truth: each view
  // has its own half of every branch. Point-to-plane ICP pulls the halves together (the bias
  // docs/registration.md describes); with the sum of both normals, two points on one circle
  // have no residual, so nothing moves.
  const Eigen::Vector3d centre(0, 0, 3);
  const Eigen::Vector3d source_camera = centre + 3.0 * Eigen::Vector3d(0, 0, -1);
  const Eigen::Vector3d target_camera =
      centre + 3.0 * Eigen::Vector3d(std::sin(144 * kDeg), 0, -std::cos(144 * kDeg));
  const auto source = BranchShells(source_camera);
  const auto target = BranchShells(target_camera);
  const open3d::geometry::KDTreeFlann tree(target);
  GatedIcpOptions options;
  options.max_normal_angle_deg = 180.0;
  options.max_distances_m = {0.06, 0.03, 0.015};
  options.iterations_per_stage = 20;
  const IcpResult plane =
      GatedPointToPlaneIcp(source, target, tree, Eigen::Isometry3d::Identity(), options);
  options.objective = IcpObjective::kSymmetric;
  const IcpResult symmetric =
      GatedPointToPlaneIcp(source, target, tree, Eigen::Isometry3d::Identity(), options);
  EXPECT_GT(plane.target_from_source.translation().norm(), 0.005);
  EXPECT_LT(symmetric.target_from_source.translation().norm(), 0.001);
  EXPECT_LT(Eigen::AngleAxisd(symmetric.target_from_source.linear()).angle(), 0.05 * kDeg);
}

TEST(GatedIcp, LineAndPlaneConstraintsPinWhatSurfacesCannot) {
  // A flat sheet only fixes z and the tilts; a line (along y) and a second plane through it fix
  // the rest but y. The line is at x = 0.1 in the target, x = 0 in the source.
  open3d::geometry::PointCloud flat;
  for (double x = -0.5; x <= 0.5; x += 0.02) {
    for (double y = -0.5; y <= 0.5; y += 0.02) flat.points_.emplace_back(x, y, 2.0);
  }
  flat.normals_.assign(flat.points_.size(), Eigen::Vector3d(0, 0, -1));
  const open3d::geometry::KDTreeFlann tree(flat);
  IcpPriors priors;
  priors.line = LineConstraint{Eigen::Vector3d(0, 0, 2),   Eigen::Vector3d::UnitY(), 0.4,
                               Eigen::Vector3d(0.1, 0, 2), Eigen::Vector3d::UnitY(), 1.0};
  GatedIcpOptions options;
  options.max_distances_m = {0.05};
  options.iterations_per_stage = 20;
  const IcpResult r = GatedPointToPlaneIcp(flat, flat, tree, Eigen::Isometry3d::Identity(), options,
                                           nullptr, nullptr, priors);
  EXPECT_NEAR(r.target_from_source.translation().x(), 0.1, 1e-3);
  EXPECT_NEAR(r.target_from_source.translation().z(), 0.0, 1e-3);
  // A plane constraint that wants the ground 5 mm lower moves z by 5 mm against the sheet's pull.
  IcpPriors ground;
  ground.plane = PlaneConstraint{
      {Eigen::Vector3d(0, 0.5, 3), Eigen::Vector3d(0.4, -0.3, 3), Eigen::Vector3d(-0.4, -0.3, 3)},
      Eigen::Vector3d::UnitZ(),
      -3.005,
      1.0};
  const IcpResult g = GatedPointToPlaneIcp(flat, flat, tree, Eigen::Isometry3d::Identity(), options,
                                           nullptr, nullptr, ground);
  EXPECT_GT(g.target_from_source.translation().z(), 0.001);
  EXPECT_LT(g.target_from_source.translation().z(), 0.005);
}

TEST(GatedIcp, EmptyOrNormallessCloudsLeaveTheStart) {
  open3d::geometry::PointCloud empty;
  const auto target = Sheet(0.05);
  const open3d::geometry::KDTreeFlann tree(target);
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  start.translation() = Eigen::Vector3d(0.1, 0, 0);
  EXPECT_EQ(GatedPointToPlaneIcp(empty, target, tree, start).target_from_source.matrix(),
            start.matrix());
  open3d::geometry::PointCloud bare = target;
  bare.normals_.clear();
  EXPECT_EQ(GatedPointToPlaneIcp(bare, target, tree, start).fitness, 0.0);
}

// Points along three branch axes (a trunk and two limbs), scattered across them by `noise_m`.
open3d::geometry::PointCloud Axes(double noise_m, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_m);
  open3d::geometry::PointCloud cloud;
  const Eigen::Vector3d fork(0, -1.0, 2.5);
  const std::pair<Eigen::Vector3d, Eigen::Vector3d> axes[] = {
      {Eigen::Vector3d(0, 0.5, 2.5), fork},
      {fork, fork + Eigen::Vector3d(0.5, -0.8, 0.1)},
      {fork, fork + Eigen::Vector3d(-0.4, -0.9, -0.2)}};
  for (const auto& [a, b] : axes) {
    for (double u = 0; u <= 1.0; u += 0.005) {
      const Eigen::Vector3d jitter(noise(rng), noise(rng), noise(rng));
      cloud.points_.push_back(a + u * (b - a) + jitter);
    }
  }
  return cloud;
}

TEST(MedialShift, RecoversTheShiftAndKeepsTheRotation) {
  const auto target = Axes(0.004, 1);
  const open3d::geometry::KDTreeFlann tree(target);
  Eigen::Isometry3d rotation = Eigen::Isometry3d::Identity();
  rotation.linear() = Eigen::AngleAxisd(0.5 * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();
  // The source is the target seen through `rotation`, moved by 2 cm towards the camera (the
  // shells' pull): the start knows the rotation but not the shift.
  auto source = Axes(0.004, 2);
  const Eigen::Vector3d pull(0.005, -0.004, -0.02);
  Eigen::Isometry3d start = rotation;
  start.translation() = pull;
  source.Transform(rotation.inverse().matrix());
  const MedialShiftResult r = AlignMedialAxes(source, target, tree, start);
  EXPECT_GT(r.matches, 500);
  EXPECT_LT((r.shift + pull).norm(), 0.003) << r.shift.transpose();
  EXPECT_TRUE(r.target_from_source.linear().isApprox(rotation.linear(), 1e-12));
  // Too far apart for the largest distance: nothing matches, the start is kept.
  Eigen::Isometry3d far = start;
  far.translation() = Eigen::Vector3d(0.5, 0, 0);
  const MedialShiftResult none = AlignMedialAxes(source, target, tree, far);
  EXPECT_TRUE(none.target_from_source.isApprox(far));
  EXPECT_EQ(none.shift.norm(), 0.0);
  // Empty clouds keep the start too.
  const open3d::geometry::PointCloud empty;
  EXPECT_TRUE(AlignMedialAxes(empty, target, tree, start).target_from_source.isApprox(start));
}

TEST(MedialShift, TheRigidFitRecoversTheRotationToo) {
  // The start is the truth moved 2 cm and turned 0.6 deg (the lean of one-sided shells): the
  // shift alone cannot undo the turn, the rigid fit does.
  const auto target = Axes(0.004, 1);
  const open3d::geometry::KDTreeFlann tree(target);
  const auto source = Axes(0.004, 2);  // truth: identity
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  start.linear() = Eigen::AngleAxisd(0.6 * kDeg, Eigen::Vector3d::UnitX()).toRotationMatrix();
  start.translation() = Eigen::Vector3d(0.004, -0.003, -0.02);
  MedialShiftOptions rigid;
  rigid.rotation = true;
  const MedialShiftResult r = AlignMedialAxes(source, target, tree, start, rigid);
  EXPECT_GT(r.matches, 500);
  EXPECT_LT(Eigen::AngleAxisd(r.target_from_source.linear()).angle(), 0.1 * kDeg);
  double squared = 0;
  for (const Eigen::Vector3d& p : source.points_) {
    squared += (r.target_from_source * p - p).squaredNorm();
  }
  // Within a few millimetres (points sampled along lines slide a little), from over 2 cm.
  EXPECT_LT(std::sqrt(squared / source.points_.size()), 0.005);
  const MedialShiftResult shifted = AlignMedialAxes(source, target, tree, start);
  EXPECT_NEAR(Eigen::AngleAxisd(shifted.target_from_source.linear()).angle(), 0.6 * kDeg, 1e-9);
  // Too far apart: the start is kept.
  Eigen::Isometry3d far = start;
  far.translation() = Eigen::Vector3d(0.5, 0, 0);
  EXPECT_TRUE(AlignMedialAxes(source, target, tree, far, rigid).target_from_source.isApprox(far));
}

TEST(Overlap, CountsGatedMatches) {
  const auto a = Sheet(0.02);
  const open3d::geometry::KDTreeFlann tree(a);
  const Overlap same = MeasureOverlap(a, a, tree, Eigen::Isometry3d::Identity(), 0.005, 45);
  EXPECT_DOUBLE_EQ(same.share, 1.0);
  EXPECT_DOUBLE_EQ(same.rmse_m, 0.0);
  const auto flipped = Sheet(0.02, 2.0, false);
  EXPECT_DOUBLE_EQ(MeasureOverlap(flipped, a, tree, Eigen::Isometry3d::Identity(), 0.005, 45).share,
                   0.0);
  EXPECT_DOUBLE_EQ(
      MeasureOverlap(flipped, a, tree, Eigen::Isometry3d::Identity(), 0.005, 180).share, 1.0);
}

TEST(GatedIcp, NonsenseOptionsAreRefused) {
  using test::RefusedField;
  EXPECT_EQ(RefusedField(GatedIcpOptions{}), "");
  EXPECT_EQ(RefusedField(GatedIcpOptions{.max_distances_m = {}}), "max_distances_m");
  EXPECT_EQ(RefusedField(GatedIcpOptions{.max_distances_m = {0.06, 0.0}}), "max_distances_m[1]");
  EXPECT_EQ(RefusedField(GatedIcpOptions{.max_normal_angle_deg = 200}), "max_normal_angle_deg");
  EXPECT_EQ(RefusedField(GatedIcpOptions{.min_planarity = -0.1}), "min_planarity");
  EXPECT_EQ(RefusedField(MedialShiftOptions{}), "");
  EXPECT_EQ(RefusedField(MedialShiftOptions{.min_matches = 2}), "min_matches");
}

}  // namespace
}  // namespace simtree::registration
