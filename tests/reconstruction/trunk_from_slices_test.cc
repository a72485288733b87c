#include "simtree/reconstruction/detail/trunk_from_slices.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "reconstruction/reconstruction_fixtures.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/units.h"

namespace simtree::reconstruction {
namespace {

// 8 cm trunk, 1.3 m, laser-like: 2 cm spacing, 3 mm noise.
std::vector<Eigen::Vector3d> Trunk(const Eigen::Vector3d& axis, double radius = 0.08) {
  return test::CylinderPoints({1.0, 2.0, -3.0}, axis, 1.3, radius, 0.02, 0.003);
}

TEST(TrunkFromSlices, MeasuresAStraightTrunk) {
  const TrunkFit fit = FitTrunkFromSlices(Trunk({0, 0, 1}), -3.0, 1.3, 0.01);
  ASSERT_TRUE(fit.found) << fit.note;
  EXPECT_NEAR(fit.cylinder.radius, 0.08, 0.08 * 0.03);
  EXPECT_TRUE(fit.slices_agree);
  EXPECT_LT(fit.cylinder.AxisDistance({1.0, 2.0, -3.0}), 0.005);
  EXPECT_GT(fit.cylinder.axis.z(), std::cos(DegToRad(2)));
}

TEST(TrunkFromSlices, CutsALeaningTrunkAcrossItsAxis) {
  // 20 degrees off vertical: horizontal cuts are ellipses 6% wider than the trunk.
  const Eigen::Vector3d axis(std::sin(DegToRad(20)), 0, std::cos(DegToRad(20)));
  const TrunkFit fit = FitTrunkFromSlices(Trunk(axis), -3.0, 1.2, 0.01);
  ASSERT_TRUE(fit.found) << fit.note;
  EXPECT_NEAR(fit.cylinder.radius, 0.08, 0.08 * 0.03);
  EXPECT_GT(fit.cylinder.axis.dot(axis), std::cos(DegToRad(4)));
}

TEST(TrunkFromSlices, ARootFlareDoesNotWidenTheTrunk) {
  // The lowest 30 cm flare from twice the radius down to it.
  std::vector<Eigen::Vector3d> points = Trunk({0, 0, 1});
  for (double z = 0.0; z < 0.3; z += 0.02) {
    const double r = 0.16 - 0.08 * z / 0.3;
    for (double a = 0; a < kTwoPi; a += 0.02 / r) {
      points.push_back({1.0 + r * std::cos(a), 2.0 + r * std::sin(a), -3.0 + z});
    }
  }
  const TrunkFit fit = FitTrunkFromSlices(points, -3.0, 1.3, 0.01);
  ASSERT_TRUE(fit.found) << fit.note;
  EXPECT_NEAR(fit.cylinder.radius, 0.08, 0.08 * 0.06);
}

TEST(TrunkFromSlices, NothingWhereNoSliceIsARing) {
  // Scattered points (a bush, noise): no slice holds a circle its points cover.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 600; ++i) points.push_back({u(rng), u(rng), 0.5 + u(rng)});
  const TrunkFit fit = FitTrunkFromSlices(points, 0.0, 1.0, 0.01);
  EXPECT_FALSE(fit.found);
  EXPECT_FALSE(fit.note.empty());
}

TEST(TrunkFromSlices, AnMsacCylinderIsTrustedOnlyWhereTheSlicesVouchForIt) {
  TrunkFit slices;
  slices.found = true;
  slices.slice_radius_m = 0.08;
  TrunkFit msac;
  msac.found = true;
  msac.inliers = 500;
  msac.length_m = 1.2;
  msac.slice_radius_m = 0.085;
  msac.slices.resize(5);
  for (TrunkSlice& s : msac.slices) s.agrees = true;
  std::string why;
  EXPECT_TRUE(TrustTrunkCylinder(msac, slices, 1.3, {}, &why)) << why;
  // The ITSMe failure: a 3.5 m cylinder from 11 points over 17 cm.
  TrunkFit huge = msac;
  huge.inliers = 11;
  huge.length_m = 0.17;
  huge.slice_radius_m = 3.5;
  EXPECT_FALSE(TrustTrunkCylinder(huge, slices, 1.3, {}, &why));
  EXPECT_NE(why.find("11 points"), std::string::npos) << why;
  TrunkFit wide = msac;
  wide.slice_radius_m = 0.2;
  EXPECT_FALSE(TrustTrunkCylinder(wide, slices, 1.3, {}, &why));
  EXPECT_NE(why.find("disagrees"), std::string::npos) << why;
  TrunkFit unsupported = msac;
  for (TrunkSlice& s : unsupported.slices) s.agrees = false;
  EXPECT_FALSE(TrustTrunkCylinder(unsupported, slices, 1.3, {}, &why));
  TrunkFit short_fit = msac;
  short_fit.length_m = 0.2;
  EXPECT_FALSE(TrustTrunkCylinder(short_fit, slices, 1.3, {}, &why));
}

TEST(TrunkFromSlices, NonsenseOptionsAreRefusedByName) {
  SliceTrunkOptions options;
  options.slices = 1;
  EXPECT_THROW(options.Validate(), OptionError);
}

}  // namespace
}  // namespace simtree::reconstruction
