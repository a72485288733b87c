#include "simtree/reconstruction/detail/trunk_cylinder.h"

#include <random>

#include <gtest/gtest.h>

#include "reconstruction/reconstruction_fixtures.h"
#include "simtree/core/units.h"

namespace simtree::reconstruction {
namespace {

// A trunk leaning 10 degrees, radius 12 cm, scanned with 3 mm noise, plus 15% stray points.
std::vector<Eigen::Vector3d> LeaningTrunk(const Eigen::Vector3d& axis) {
  auto points = test::CylinderPoints({0.3, -0.2, 1.0}, axis, 0.8, 0.12, 0.01, 0.003);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  const size_t strays = points.size() * 15 / 100;
  for (size_t i = 0; i < strays; ++i) points.push_back({0.3 + u(rng), -0.2 + u(rng), 1.4 + u(rng)});
  return points;
}

TEST(TrunkCylinder, MsacFindsRadiusAndAxisDespiteNoiseAndOutliers) {
  const Eigen::Vector3d axis =
      Eigen::Vector3d(std::sin(DegToRad(10)), 0, std::cos(DegToRad(10))).normalized();
  const TrunkFit fit = FitTrunkCylinder(LeaningTrunk(axis), 1.0, 0.008);
  ASSERT_TRUE(fit.found) << fit.note;
  EXPECT_NEAR(fit.cylinder.radius, 0.12, 0.12 * 0.03);
  EXPECT_GT(std::abs(fit.cylinder.axis.dot(axis)), std::cos(DegToRad(2)));
  EXPECT_NEAR(fit.base.z(), 1.0, 1e-9);
  EXPECT_LT(fit.cylinder.AxisDistance({0.3, -0.2, 1.0}), 0.01);  // the base is on the axis
  EXPECT_NEAR(fit.rms_m, 0.003, 0.0015);
  EXPECT_TRUE(fit.slices_agree);
  ASSERT_EQ(fit.slices.size(), 5u);
  for (const TrunkSlice& s : fit.slices) EXPECT_NEAR(s.radius_m, 0.12, 0.012);
  EXPECT_NEAR(fit.slice_radius_m, 0.12, 0.006);
}

TEST(TrunkCylinder, AForkAboveShortensTheFitToTheSlicesThatAgree) {
  // 0.6 m of trunk, then two 7 cm stems side by side (together much wider than the trunk).
  auto points = test::CylinderPoints({0, 0, 0}, {0, 0, 1}, 0.6, 0.1, 0.01, 0.002);
  for (const double x : {-0.12, 0.12}) {
    const auto stem = test::CylinderPoints({x, 0, 0.6}, {0, 0, 1}, 0.4, 0.07, 0.01, 0.002);
    points.insert(points.end(), stem.begin(), stem.end());
  }
  const TrunkFit fit = FitTrunkCylinder(points, 0.0, 0.006);
  ASSERT_TRUE(fit.found) << fit.note;
  EXPECT_NEAR(fit.cylinder.radius, 0.1, 0.005);
  std::string slices;
  for (const TrunkSlice& sl : fit.slices) {
    slices += std::to_string(sl.from_m) + ":" + std::to_string(sl.radius_m) + "/" +
              std::to_string(sl.centre_offset_m) + (sl.agrees ? "+ " : "- ");
  }
  EXPECT_LE(fit.length_m, 0.65) << slices;
  EXPECT_FALSE(fit.note.empty());
}

TEST(TrunkCylinder, AThinTrunkBlurredAsWideAsItsRadiusIsRebuiltFromTheSliceCircles) {
  // A 2.6 cm trunk leaning 4 degrees, every point moved 1 cm (std) in 3D: a blurred ring in
  // which a wider tilted cylinder can hold more points within the MSAC band than the true one.
  const Eigen::Vector3d axis =
      Eigen::Vector3d(std::sin(DegToRad(4)), 0, std::cos(DegToRad(4))).normalized();
  auto points = test::CylinderPoints({0, 0, 0}, axis, 0.8, 0.026, 0.004);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> gauss(0.0, 0.01);
  for (Eigen::Vector3d& p : points) p += Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
  const TrunkFit fit = FitTrunkCylinder(points, 0.0, 0.009);
  ASSERT_TRUE(fit.found) << fit.note;
  EXPECT_NEAR(fit.cylinder.radius, 0.026, 0.026 * 0.1) << fit.note;
  EXPECT_NEAR(fit.slice_radius_m, 0.026, 0.026 * 0.1);
  EXPECT_GT(fit.cylinder.axis.dot(axis), std::cos(DegToRad(3))) << fit.note;
  EXPECT_LT(fit.cylinder.AxisDistance({0, 0, 0}), 0.008);
}

TEST(TrunkCylinder, RobustCircleIgnoresABranchBesideTheTrunk) {
  // A ring of 5 cm radius and, beside it, a second smaller ring (a low branch) with a third as many
  // points: the plain fit is dragged toward it, the robust one is not.
  std::vector<Eigen::Vector3d> slab;
  for (int i = 0; i < 90; ++i) {
    const double a = kTwoPi * i / 90;
    slab.push_back({0.05 * std::cos(a), 0.05 * std::sin(a), 0.01 * (i % 3)});
  }
  for (int i = 0; i < 30; ++i) {
    const double a = kTwoPi * i / 30;
    slab.push_back({0.09 + 0.015 * std::cos(a), 0.015 * std::sin(a), 0.0});
  }
  Eigen::Vector3d centre;
  double radius = 0.0;
  ASSERT_TRUE(FitCircle(slab, {0, 0, 0}, Eigen::Vector3d::UnitZ(), &centre, &radius));
  EXPECT_GT(std::abs(radius - 0.05) + centre.head<2>().norm(), 0.005);
  ASSERT_TRUE(FitCircleRobust(slab, {0, 0, 0}, Eigen::Vector3d::UnitZ(), 0.002, &centre, &radius));
  EXPECT_NEAR(radius, 0.05, 1e-3);
  EXPECT_LT(centre.head<2>().norm(), 1e-3);
  EXPECT_NEAR(centre.z(), 0.0, 1e-12);  // in the plane through the origin
  const std::vector<Eigen::Vector3d> two = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_FALSE(FitCircleRobust(two, {0, 0, 0}, Eigen::Vector3d::UnitZ(), 0.002, &centre, &radius));
}

TEST(TrunkCylinder, TooFewPointsOrNoCylinderIsSaid) {
  const std::vector<Eigen::Vector3d> few = {{0, 0, 0}, {0, 0, 1}};
  const TrunkFit none = FitTrunkCylinder(few, 0.0, 0.01);
  EXPECT_FALSE(none.found);
  EXPECT_NE(none.note.find("too few"), std::string::npos);
  // A horizontal log is no trunk (beyond the tilt limit).
  const auto log = test::CylinderPoints({0, 0, 0}, {1, 0, 0}, 1.0, 0.1, 0.01);
  EXPECT_FALSE(FitTrunkCylinder(log, 0.0, 0.01).found);
}

TEST(TrunkCylinder, CircleFitRecoversAPartialArc) {
  // A quarter... a third of a circle of radius 5 cm around (1, 2) in the plane z = 3.
  std::vector<Eigen::Vector3d> arc;
  for (int i = 0; i <= 20; ++i) {
    const double t = kTwoPi / 3 * i / 20;
    arc.push_back({1 + 0.05 * std::cos(t), 2 + 0.05 * std::sin(t), 3 + 0.001 * (i % 3)});
  }
  Eigen::Vector3d centre;
  double radius = 0;
  ASSERT_TRUE(FitCircle(arc, {1, 2, 3}, Eigen::Vector3d::UnitZ(), &centre, &radius));
  EXPECT_NEAR(radius, 0.05, 1e-6);
  EXPECT_NEAR((centre - Eigen::Vector3d(1, 2, 3)).head<2>().norm(), 0.0, 1e-6);
  const std::vector<Eigen::Vector3d> two = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_FALSE(FitCircle(two, {0, 0, 0}, Eigen::Vector3d::UnitZ(), &centre, &radius));
}

}  // namespace
}  // namespace simtree::reconstruction
