#include "simtree/synth/detail/fem_model.h"

#include <cmath>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "core/tree_fixtures.h"
#include "simtree/core/error.h"
#include "simtree/core/units.h"
#include "simtree/synth/detail/fem_modes.h"
#include "simtree/synth/detail/fem_response.h"
#include "synth/fem_test_trees.h"

namespace simtree::synth {
namespace {

using ::testing::HasSubstr;

// Tip deflection P L^3 / 3EI, in two planes and along an axis that is not a world axis.
TEST(FemModel, CantileverTipDeflectionMatchesClosedForm) {
  const WoodProperties wood = test::TestWood();
  const double length = 2.0, radius = 0.02, load = 10.0;
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, 3).normalized();
  const FemModel model(test::UniformCantilever(axis, length, radius), wood);
  const double ei = wood.youngs_modulus_pa * test::SecondMoment(radius);
  const double expected = load * std::pow(length, 3) / (3 * ei);
  const Eigen::Vector3d across_1 = axis.unitOrthogonal();
  const Eigen::Vector3d across_2 = axis.cross(across_1);
  for (const Eigen::Vector3d& direction :
       {across_1, across_2, (across_1 + across_2).normalized()}) {
    const Eigen::VectorXd x = SolveStatic(model, model.PointLoad(0, length, load * direction));
    const PointMotion tip = model.MotionAt(x, 0, length);
    EXPECT_NEAR(tip.displacement.dot(direction) / expected, 1.0, 1e-6);
    // The tip turns by P L^2 / 2EI about axis x direction.
    const double slope = load * length * length / (2 * ei);
    EXPECT_NEAR(tip.rotation.dot(axis.cross(direction)) / slope, 1.0, 1e-6);
    // Mid-span: P x^2 (3L - x) / 6EI.
    const double xm = 0.75;
    const double mid = load * xm * xm * (3 * length - xm) / (6 * ei);
    EXPECT_NEAR(model.MotionAt(x, 0, xm).displacement.dot(direction) / mid, 1.0, 1e-6);
  }
}

TEST(FemModel, CantileverTwistAndStretchMatchClosedForm) {
  const WoodProperties wood = test::TestWood();
  const double length = 1.5, radius = 0.025;
  const Eigen::Vector3d axis = Eigen::Vector3d(-1, 0.5, 2).normalized();
  const FemModel model(test::UniformCantilever(axis, length, radius), wood);
  // Twist T L / GJ.
  const double torque = 20.0;
  const double gj = wood.shear_modulus_pa * 2 * test::SecondMoment(radius);
  Eigen::VectorXd x =
      SolveStatic(model, model.PointLoad(0, length, Eigen::Vector3d::Zero(), torque * axis));
  EXPECT_NEAR(model.MotionAt(x, 0, length).rotation.dot(axis) / (torque * length / gj), 1.0, 1e-9);
  // Stretch P L / EA.
  const double pull = 1000.0;
  x = SolveStatic(model, model.PointLoad(0, length, pull * axis));
  const double ea = wood.youngs_modulus_pa * kPi * radius * radius;
  EXPECT_NEAR(model.MotionAt(x, 0, length).displacement.dot(axis) / (pull * length / ea), 1.0,
              1e-9);
}

// On a root plate of stiffness k = ratio EI / L the base tilts by P L / k under a top pull,
// which adds P L^2 / k to the bending's P L^3 / 3EI; a twist is held as on a clamp.
TEST(FemModel, RootPlateTiltsUnderAPullAndHoldsATwist) {
  const WoodProperties wood = test::TestWood();
  const double length = 2.0, radius = 0.02, load = 10.0, ratio = 1.5;
  const Tree tree = test::UniformCantilever({0, 0, 1}, length, radius);
  const FemModel clamped(tree, wood);
  const FemModel model(tree, wood, {.root_plate_stiffness_ratio = ratio});
  ASSERT_TRUE(model.has_root_plate());
  EXPECT_EQ(model.dof_count(), clamped.dof_count() + 2);
  const double ei = wood.youngs_modulus_pa * test::SecondMoment(radius);
  const double k = ratio * ei / length;
  EXPECT_NEAR(model.root_plate_stiffness() / k, 1.0, 1e-12);
  for (const Eigen::Vector3d& direction : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
                                           Eigen::Vector3d(1, 1, 0).normalized()}) {
    const Eigen::VectorXd x = SolveStatic(model, model.PointLoad(0, length, load * direction));
    const double expected = load * std::pow(length, 3) / (3 * ei) + load * length * length / k;
    EXPECT_NEAR(model.MotionAt(x, 0, length).displacement.dot(direction) / expected, 1.0, 1e-6);
    // The base tilts but stays where it is.
    const PointMotion base = model.NodeMap(0).Apply(x);
    EXPECT_NEAR(base.rotation.dot(Eigen::Vector3d::UnitZ().cross(direction)) / (load * length / k),
                1.0, 1e-6);
    EXPECT_EQ(base.displacement.norm(), 0.0);
    EXPECT_EQ(model.Pose(x).node(0, 0), tree.trunk().base().position);
  }
  const double torque = 20.0;
  const Eigen::Vector3d twist(0, 0, torque);
  const auto turn = [&](const FemModel& m) {
    return m
        .MotionAt(SolveStatic(m, m.PointLoad(0, length, Eigen::Vector3d::Zero(), twist)), 0, length)
        .rotation.z();
  };
  EXPECT_NEAR(turn(model) / turn(clamped), 1.0, 1e-9);
}

// A stiff stem on a soft root plate rocks as a rigid body: omega^2 = k / (rho A L^3 / 3).
TEST(FemModel, StiffStemOnASoftRootPlateRocksRigidly) {
  const WoodProperties wood = test::TestWood();
  const double length = 2.0, radius = 0.02, ratio = 0.01;
  const FemModel model(test::UniformCantilever({0, 0, 1}, length, radius), wood,
                       {.root_plate_stiffness_ratio = ratio});
  ModesOptions options;
  options.count = 1;
  const double f = ComputeModes(model, options).frequency_hz[0];
  const double inertia = wood.density_kg_m3 * kPi * radius * radius * std::pow(length, 3) / 3;
  const double rigid = std::sqrt(model.root_plate_stiffness() / inertia) / kTwoPi;
  // The stem's own bending lowers it by about ratio / 10.
  EXPECT_LT(f, rigid);
  EXPECT_GT(f, 0.99 * rigid);
}

TEST(FemModel, OwnWeightOfAHorizontalCantileverIsQL4Over8EI) {
  const WoodProperties wood = test::TestWood();
  const double length = 1.2, radius = 0.015;
  const FemModel model(test::UniformCantilever({1, 1, 0}, length, radius), wood);
  const double q = wood.density_kg_m3 * kPi * radius * radius * kGravity;
  const double ei = wood.youngs_modulus_pa * test::SecondMoment(radius);
  const Eigen::VectorXd x = SolveStatic(model, model.GravityLoad());
  EXPECT_NEAR(model.MotionAt(x, 0, length).displacement.z() / (-q * std::pow(length, 4) / (8 * ei)),
              1.0, 1e-6);
  EXPECT_NEAR(model.total_mass_kg(), wood.density_kg_m3 * kPi * radius * radius * length, 1e-12);
}

// Tip deflection of a tapered cantilever: (P/E) integral_0^L (L - x)^2 / I(x) dx, the integral
// taken here by Simpson's rule on 20,000 intervals, independent of the FEM.
double TaperedTipDeflection(const WoodProperties& wood, double length, double r0, double r1,
                            double load) {
  const int n = 20000;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double x = length * i / n;
    const double r = r0 + (r1 - r0) * x / length;
    const double f = (length - x) * (length - x) / test::SecondMoment(r);
    sum += f * (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2));
  }
  return load / wood.youngs_modulus_pa * sum * (length / n) / 3.0;
}

TEST(FemModel, TaperedBranchConvergesToTheClosedFormAsElementsShrink) {
  const WoodProperties wood = test::TestWood();
  const double length = 2.0, r0 = 0.05, r1 = 0.01, load = 5.0;
  // Two tree segments only: the element length option alone sets the mesh.
  const Tree tree = test::Cantilever({0, 0, 0}, {0, 0, 1}, length, 2,
                                     [&](double t) { return r0 + (r1 - r0) * t; });
  const double expected = TaperedTipDeflection(wood, length, r0, r1, load);
  double previous_error = 1.0;
  for (double h : {1.0, 0.5, 0.25, 0.125, 0.0625}) {
    const FemModel model(tree, wood, {.max_element_length_m = h});
    EXPECT_EQ(model.element_count(), static_cast<int>(std::lround(length / h)));
    const Eigen::VectorXd x = SolveStatic(model, model.PointLoad(0, length, {load, 0, 0}));
    const double error = std::abs(model.MotionAt(x, 0, length).displacement.x() / expected - 1);
    EXPECT_LT(error, previous_error) << h;
    previous_error = error;
  }
  EXPECT_LT(previous_error, 1e-3);
}

TEST(FemModel, MeshSharesJointsAndSplitsLongSegments) {
  const Tree tree = test::SmallTree();  // 5 + 4 + 4 + 3 nodes, three children
  const FemModel coarse(tree, test::TestWood(), {.max_element_length_m = 1.0});
  // Each child's first node is its parent's node.
  EXPECT_EQ(coarse.node_count(), tree.NodeCount() - 3);
  EXPECT_EQ(coarse.element_count(), coarse.node_count() - 1);  // a tree graph
  EXPECT_EQ(coarse.dof_count(), 6 * (coarse.node_count() - 1));
  for (int b = 1; b < tree.size(); ++b) {
    const Branch& branch = tree.branches[b];
    EXPECT_EQ(coarse.tree_node(b, 0), coarse.tree_node(branch.parent, branch.parent_node));
  }
  // Trunk segments are 0.25 m: at most 0.1 m makes three elements of each.
  const FemModel fine(tree, test::TestWood(), {.max_element_length_m = 0.1});
  EXPECT_GT(fine.node_count(), coarse.node_count());
  for (int e = 0; e < fine.element_count(); ++e) {
    EXPECT_LE(fine.element(e).Length(), 0.1 + 1e-9);
  }
  EXPECT_NEAR(fine.total_mass_kg(), coarse.total_mass_kg(), 1e-12 * coarse.total_mass_kg());
}

TEST(FemModel, PoseMovesTreeNodesAndKeepsJointsTogether) {
  const Tree tree = test::SmallTree();
  const FemModel model(tree, test::TestWood());
  const Eigen::VectorXd x = SolveStatic(model, model.PointLoad(3, 0.2, {0, 0, -50}));
  const TreePose pose = model.Pose(x);
  ASSERT_EQ(pose.node_count(), tree.NodeCount());
  EXPECT_EQ(pose.node(0, 0), tree.branches[0].nodes[0].position);  // clamped
  for (const Branch& b : tree.branches) {
    for (int i = 0; i < static_cast<int>(b.nodes.size()); ++i) {
      const Eigen::Vector3d moved = pose.node(b.id, i) - b.nodes[i].position;
      // The same displacement as the shape functions give at the node's arc length.
      const double s = b.ArcLengths()[i];
      EXPECT_LT((moved - model.MotionAt(x, b.id, s).displacement).norm(), 1e-12);
    }
    if (!b.is_trunk()) {
      const Eigen::Vector3d gap_rest =
          b.nodes[0].position - tree.branches[b.parent].nodes[b.parent_node].position;
      const Eigen::Vector3d gap_now = pose.node(b.id, 0) - pose.node(b.parent, b.parent_node);
      EXPECT_LT((gap_now - gap_rest).norm(), 1e-12);
    }
  }
  // Pulling the grandchild down moves its tip down.
  EXPECT_LT(pose.node(3, 2).z() - tree.branches[3].nodes[2].position.z(), 0.0);
}

TEST(FemModel, BadInputIsAnInputError) {
  const WoodProperties wood = test::TestWood();
  EXPECT_THAT(test::ErrorOf<InputError>([&] { FemModel(Tree{}, wood); }),
              HasSubstr("at least one branch"));
  Tree tree = test::SmallTree();
  tree.branches[2].nodes[1].radius = 0.0;
  EXPECT_THAT(test::ErrorOf<InputError>([&] { FemModel(tree, wood); }),
              HasSubstr("branches[2].nodes[1].radius"));
  tree = test::SmallTree();
  tree.branches[1].nodes[2].position.x() = kNaN;
  EXPECT_THAT(test::ErrorOf<InputError>([&] { FemModel(tree, wood); }), HasSubstr("position"));
  WoodProperties bad = wood;
  bad.youngs_modulus_pa = kNaN;
  EXPECT_THAT(test::ErrorOf<InputError>([&] { FemModel(test::SmallTree(), bad); }),
              HasSubstr("youngs_modulus_pa"));
  bad = wood;
  bad.rayleigh_beta = -1e-3;
  EXPECT_THAT(test::ErrorOf<InputError>([&] { FemModel(test::SmallTree(), bad); }),
              HasSubstr("rayleigh_beta"));
  EXPECT_THAT(test::ErrorOf<InputError>(
                  [&] { FemModel(test::SmallTree(), wood, {.max_element_length_m = 0}); }),
              HasSubstr("max_element_length_m"));
  for (double ratio : {-1.0, kNaN}) {
    EXPECT_THAT(test::ErrorOf<InputError>([&] {
                  FemModel(test::SmallTree(), wood, {.root_plate_stiffness_ratio = ratio});
                }),
                HasSubstr("root_plate_stiffness_ratio"));
  }
  // A branch of coincident nodes only has nothing to bend.
  Tree point = test::Cantilever({0, 0, 0}, {0, 0, 1}, 0.0, 3, [](double) { return 0.01; });
  EXPECT_THAT(test::ErrorOf<InputError>([&] { FemModel(point, wood); }),
              HasSubstr("non-zero length"));

  const FemModel model(test::SmallTree(), wood);
  EXPECT_THAT(test::ErrorOf<InputError>([&] {
                model.PointLoad(7, 0.1, {1, 0, 0});
              }),
              HasSubstr("branch: expected a branch id in [0, 3], got 7"));
  EXPECT_THAT(test::ErrorOf<InputError>([&] {
                model.PointLoad(-1, 0.1, {1, 0, 0});
              }),
              HasSubstr("branch"));
  EXPECT_THAT(test::ErrorOf<InputError>([&] {
                model.PointLoad(1, 5.0, {1, 0, 0});
              }),
              HasSubstr("arc_length"));
  EXPECT_THAT(test::ErrorOf<InputError>([&] {
                model.PointLoad(1, kNaN, {1, 0, 0});
              }),
              HasSubstr("arc_length"));
  EXPECT_THAT(test::ErrorOf<InputError>([&] {
                model.PointLoad(1, 0.1, {kNaN, 0, 0});
              }),
              HasSubstr("finite"));
  EXPECT_THAT(test::ErrorOf<InputError>([&] { model.Pose(Eigen::VectorXd::Zero(5)); }),
              HasSubstr("expected"));
  EXPECT_THAT(test::ErrorOf<InputError>([&] { SolveStatic(model, Eigen::VectorXd::Zero(3)); }),
              HasSubstr("force"));
  Eigen::VectorXd f = Eigen::VectorXd::Zero(model.dof_count());
  f[4] = kNaN;
  EXPECT_THAT(test::ErrorOf<InputError>([&] { SolveStatic(model, f); }), HasSubstr("NaN"));
}

TEST(FemModel, MergesCoincidentNodes) {
  // A tree file with a repeated node (zero-length segment) is meshed as if it were not there.
  Tree tree = test::UniformCantilever({0, 0, 1}, 1.0, 0.02, 4);
  Tree doubled = tree;
  doubled.branches[0].nodes.insert(doubled.branches[0].nodes.begin() + 2,
                                   doubled.branches[0].nodes[2]);
  const FemModel a(tree, test::TestWood()), b(doubled, test::TestWood());
  EXPECT_EQ(a.node_count(), b.node_count());
  EXPECT_EQ(b.tree_node(0, 2), b.tree_node(0, 3));
  const Eigen::VectorXd xa = SolveStatic(a, a.PointLoad(0, 1.0, {1, 0, 0}));
  const Eigen::VectorXd xb = SolveStatic(b, b.PointLoad(0, 1.0, {1, 0, 0}));
  EXPECT_LT((xa - xb).norm(), 1e-12 * xa.norm());
  EXPECT_EQ(b.Pose(xb).node(0, 3), b.Pose(xb).node(0, 2));
}

}  // namespace
}  // namespace simtree::synth
