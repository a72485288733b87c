#include "simtree/synth/detail/fem_beam_element.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include "simtree/core/units.h"
#include "synth/fem_test_trees.h"

namespace simtree::synth {
namespace {

BeamElement SomeElement(double r_a, double r_b) {
  BeamElement e;
  e.a = {0.2, -0.4, 1.0};
  e.b = e.a + 0.3 * Eigen::Vector3d(1, 2, 3).normalized();
  e.radius_a = r_a;
  e.radius_b = r_b;
  return e;
}

// The 12 world degrees of freedom of a rigid motion (translation t, small rotation w about the
// world origin) of the element's two nodes.
Vector12d RigidMotion(const BeamElement& e, const Eigen::Vector3d& t, const Eigen::Vector3d& w) {
  Vector12d x;
  x << t + w.cross(e.a), w, t + w.cross(e.b), w;
  return x;
}

TEST(FemBeamElement, RigidMotionsCostNoStrainEnergy) {
  const WoodProperties wood = test::TestWood();
  const BeamElement e = SomeElement(0.03, 0.018);
  const Matrix12d k = e.Stiffness(wood);
  EXPECT_LT((k - k.transpose()).norm(), 1e-9 * k.norm());
  const double scale = k.norm();
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT((k * RigidMotion(e, Eigen::Vector3d::Unit(i), Eigen::Vector3d::Zero())).norm(),
              1e-9 * scale);
    EXPECT_LT((k * RigidMotion(e, Eigen::Vector3d::Zero(), Eigen::Vector3d::Unit(i))).norm(),
              1e-9 * scale);
  }
  // Six rigid motions, six deformation modes with positive stiffness.
  Eigen::SelfAdjointEigenSolver<Matrix12d> eig(k);
  int zero = 0;
  for (int i = 0; i < 12; ++i) {
    EXPECT_GT(eig.eigenvalues()[i], -1e-9 * scale);
    zero += eig.eigenvalues()[i] < 1e-9 * scale;
  }
  EXPECT_EQ(zero, 6);
}

TEST(FemBeamElement, UniformElementHasTheTextbookStiffness) {
  // Along world X the local axes are x, then y and z across: compare with the closed-form
  // entries EA/L, GJ/L, 12EI/L^3, 6EI/L^2, 4EI/L, 2EI/L.
  const WoodProperties wood = test::TestWood();
  BeamElement e;
  e.a = Eigen::Vector3d::Zero();
  e.b = {0.4, 0, 0};
  e.radius_a = e.radius_b = 0.02;
  const Matrix12d k = e.Stiffness(wood);
  const double l = 0.4, r = 0.02;
  const double ea = wood.youngs_modulus_pa * kPi * r * r;
  const double ei = wood.youngs_modulus_pa * test::SecondMoment(r);
  const double gj = wood.shear_modulus_pa * 2 * test::SecondMoment(r);
  const double tol = 1e-9;
  EXPECT_NEAR(k(0, 0) / (ea / l), 1.0, tol);
  EXPECT_NEAR(k(0, 6) / (-ea / l), 1.0, tol);
  EXPECT_NEAR(k(3, 3) / (gj / l), 1.0, tol);
  // Bending about any transverse axis (the section is round): translation across, rotation.
  for (int across : {1, 2}) {
    EXPECT_NEAR(k(across, across) / (12 * ei / (l * l * l)), 1.0, tol) << across;
    EXPECT_NEAR(k(across, across + 6) / (-12 * ei / (l * l * l)), 1.0, tol) << across;
  }
  for (int rot : {4, 5}) {
    EXPECT_NEAR(k(rot, rot) / (4 * ei / l), 1.0, tol) << rot;
    EXPECT_NEAR(k(rot, rot + 6) / (2 * ei / l), 1.0, tol) << rot;
  }
  EXPECT_NEAR(std::abs(k(1, 5)) / (6 * ei / (l * l)), 1.0, tol);
  EXPECT_NEAR(std::abs(k(2, 4)) / (6 * ei / (l * l)), 1.0, tol);
}

TEST(FemBeamElement, MassOfARigidTranslationIsTheWoodsMass) {
  const WoodProperties wood = test::TestWood();
  const BeamElement e = SomeElement(0.03, 0.01);
  const Matrix12d m = e.Mass(wood);
  // Frustum volume pi L (r_a^2 + r_a r_b + r_b^2) / 3.
  const double volume = kPi * e.Length() * (0.03 * 0.03 + 0.03 * 0.01 + 0.01 * 0.01) / 3.0;
  for (int i = 0; i < 3; ++i) {
    const Vector12d t = RigidMotion(e, Eigen::Vector3d::Unit(i), Eigen::Vector3d::Zero());
    EXPECT_NEAR(t.dot(m * t), wood.density_kg_m3 * volume, 1e-12);
  }
  Eigen::SelfAdjointEigenSolver<Matrix12d> eig(m);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);  // positive definite, rotary inertia included
  // The weight is the mass under gravity, wherever the element points.
  const Vector12d w = e.Weight(wood, {0, 0, -kGravity});
  EXPECT_NEAR(w[2] + w[8], -kGravity * wood.density_kg_m3 * volume, 1e-12);
  EXPECT_NEAR(w[0] + w[6], 0.0, 1e-12);
}

TEST(FemBeamElement, PointOperatorInterpolatesNodesAndRigidMotion) {
  const BeamElement e = SomeElement(0.02, 0.02);
  const Eigen::Vector3d t(0.01, -0.02, 0.03), w(0.1, 0.2, -0.05);
  const Vector12d x = RigidMotion(e, t, w);
  for (double xi : {0.0, 0.3, 1.0}) {
    const Eigen::Matrix<double, 6, 1> m = e.PointOperator(xi) * x;
    const Eigen::Vector3d p = e.a + xi * (e.b - e.a);
    EXPECT_LT((m.head<3>() - (t + w.cross(p))).norm(), 1e-12) << xi;
    EXPECT_LT((m.tail<3>() - w).norm(), 1e-12) << xi;
  }
}

}  // namespace
}  // namespace simtree::synth
