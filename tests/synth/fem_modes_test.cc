#include "simtree/synth/detail/fem_modes.h"

#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/core/tree_file.h"
#include "synth/fem_test_trees.h"
#include "test_util.h"

namespace simtree::synth {
namespace {

void ExpectMassOrthonormal(const FemModel& model, const ModalBasis& modes, double tol) {
  const Eigen::MatrixXd gram = modes.shapes.transpose() * (model.mass() * modes.shapes);
  EXPECT_LT((gram - Eigen::MatrixXd::Identity(modes.count(), modes.count())).cwiseAbs().maxCoeff(),
            tol);
  const Eigen::MatrixXd stiffness = modes.shapes.transpose() * (model.stiffness() * modes.shapes);
  for (int i = 0; i < modes.count(); ++i) {
    EXPECT_NEAR(stiffness(i, i) / (modes.omega[i] * modes.omega[i]), 1.0, tol);
  }
}

// A uniform cantilever's first two bending frequencies, 1.8751^2 and 4.6941^2 sqrt(EI / rho A L^4)
// / 2 pi, each twice (two bending planes of a round section), within 1% (rotary inertia, which
// the closed form leaves out, lowers them by a few parts in 10^5 here).
TEST(FemModes, UniformCantileverMatchesClosedForm) {
  const WoodProperties wood = test::TestWood();
  const double length = 2.0, radius = 0.02;
  const FemModel model(test::UniformCantilever({1, 2, 3}, length, radius, 20), wood);
  const ModalBasis modes = ComputeModes(model, {.count = 6, .dense_limit = 0});  // Spectra
  ASSERT_EQ(modes.count(), 6);
  const double f1 = test::CantileverFrequencyHz(test::kBetaL1, wood, length, radius);
  const double f2 = test::CantileverFrequencyHz(test::kBetaL2, wood, length, radius);
  for (int i : {0, 1}) EXPECT_NEAR(modes.frequency_hz[i] / f1, 1.0, 1e-3) << i;
  for (int i : {2, 3}) EXPECT_NEAR(modes.frequency_hz[i] / f2, 1.0, 1e-3) << i;
  ExpectMassOrthonormal(model, modes, 1e-8);
  for (int i = 1; i < modes.count(); ++i) {
    EXPECT_GE(modes.frequency_hz[i], modes.frequency_hz[i - 1]);
  }
}

// Young wood (wood.h): a uniform cantilever thinner than the mature radius bends with E times
// (r / r_mature)^k, so its frequencies are the closed form's times that factor's square root.
TEST(FemModes, YoungWoodCantileverMatchesClosedFormWithItsModulus) {
  WoodProperties wood = test::TestWood();
  const double length = 2.0, radius = 0.02;
  const double f1 = test::CantileverFrequencyHz(test::kBetaL1, wood, length, radius);
  wood.mature_radius_m = 0.08;
  wood.young_wood_exponent = 1.0;  // a quarter of E at a quarter of the mature radius
  const FemModel model(test::UniformCantilever({1, 2, 3}, length, radius, 20), wood);
  const ModalBasis modes = ComputeModes(model, {.count = 2});
  ASSERT_EQ(modes.count(), 2);
  for (int i : {0, 1}) EXPECT_NEAR(modes.frequency_hz[i] / (0.5 * f1), 1.0, 1e-3) << i;
}

TEST(FemModes, DenseAndSparseSolversAgree) {
  WoodProperties wood = test::TestWood();
  wood.SetRayleighFromRatios(1.0, 0.04, 10.0, 0.03);
  const FemModel model(test::YTree(), wood, {.max_element_length_m = 0.1});
  const ModalBasis dense = ComputeModes(model, {.count = 12, .dense_limit = 1000});
  const ModalBasis sparse = ComputeModes(model, {.count = 12, .dense_limit = 0});
  ASSERT_EQ(dense.count(), 12);
  ASSERT_EQ(sparse.count(), 12);
  for (int i = 0; i < 12; ++i) {
    EXPECT_NEAR(sparse.frequency_hz[i] / dense.frequency_hz[i], 1.0, 1e-9) << i;
    EXPECT_NEAR(sparse.damping_ratio[i], wood.DampingRatioAt(sparse.frequency_hz[i]), 1e-12);
  }
  ExpectMassOrthonormal(model, sparse, 1e-8);
  ExpectMassOrthonormal(model, dense, 1e-8);
}

TEST(FemModes, CoverFrequencyExtendsTheCount) {
  const FemModel model(test::YTree(), test::TestWood());
  const ModalBasis few = ComputeModes(model, {.count = 2, .dense_limit = 0});
  ASSERT_EQ(few.count(), 2);
  const double cover = 3.0 * few.frequency_hz[1];
  const ModalBasis more =
      ComputeModes(model, {.count = 2, .cover_frequency_hz = cover, .dense_limit = 0});
  EXPECT_GT(more.count(), 2);
  EXPECT_GE(more.frequency_hz[more.count() - 1], cover);
}

// The Y is its own mirror image under x -> -x, and that mirror commutes with K and M: every
// mode of a distinct frequency is either symmetric or antisymmetric. The children are much
// thinner than the trunk, so their modes come in close pairs: in phase and out of phase.
TEST(FemModes, SymmetricChildrenGivePairedModes) {
  const FemModel model(test::YTree(0.08, 0.02), test::TestWood(), {.max_element_length_m = 0.1});
  const ModalBasis modes = ComputeModes(model, {.count = 16, .dense_limit = 0});
  // The mirror on the degrees of freedom: node to mirrored node, translations diag(-1, 1, 1),
  // rotations (a pseudovector) diag(1, -1, -1).
  const int n = model.dof_count();
  Eigen::MatrixXd mirror = Eigen::MatrixXd::Zero(n, n);
  for (int a = 1; a < model.node_count(); ++a) {
    Eigen::Vector3d p = model.node_position(a);
    p.x() = -p.x();
    int b = -1;
    for (int c = 1; c < model.node_count(); ++c) {
      if ((model.node_position(c) - p).norm() < 1e-9) b = c;
    }
    ASSERT_GE(b, 0) << "node " << a << " has no mirror image";
    const double sign[6] = {-1, 1, 1, 1, -1, -1};
    for (int k = 0; k < 6; ++k) mirror(model.node_dof(b) + k, model.node_dof(a) + k) = sign[k];
  }
  std::vector<int> parity(modes.count(), 0);
  for (int i = 0; i < modes.count(); ++i) {
    const bool distinct =
        (i == 0 || modes.frequency_hz[i] > 1.0001 * modes.frequency_hz[i - 1]) &&
        (i + 1 == modes.count() || modes.frequency_hz[i + 1] > 1.0001 * modes.frequency_hz[i]);
    if (!distinct) continue;
    const Eigen::VectorXd phi = modes.shapes.col(i);
    const double overlap = phi.dot(model.mass() * (mirror * phi));
    EXPECT_NEAR(std::abs(overlap), 1.0, 1e-6) << "mode " << i;
    parity[i] = overlap > 0 ? 1 : -1;
  }
  // Child modes: most of the kinetic energy in the children. In each bending plane (out of the
  // Y's plane, in it) the two lowest pair up within 5%, one of each parity.
  for (bool out_of_plane : {true, false}) {
    std::vector<int> child_modes;
    for (int i = 0; i < modes.count(); ++i) {
      const Eigen::VectorXd phi = modes.shapes.col(i);
      Eigen::VectorXd in_children = Eigen::VectorXd::Zero(n);
      double along_y = 0.0, all = 0.0;
      for (int node = 1; node < model.node_count(); ++node) {
        const int dof = model.node_dof(node);
        if (model.node_position(node).z() > 1.0 + 1e-9) {
          in_children.segment<6>(dof) = phi.segment<6>(dof);
        }
        along_y += phi[dof + 1] * phi[dof + 1];
        all += phi.segment<3>(dof).squaredNorm();
      }
      const bool child = in_children.dot(model.mass() * in_children) > 0.8;
      if (child && (along_y > 0.5 * all) == out_of_plane) child_modes.push_back(i);
    }
    ASSERT_GE(child_modes.size(), 2u) << out_of_plane;
    const int a = child_modes[0], b = child_modes[1];
    EXPECT_NEAR(modes.frequency_hz[b] / modes.frequency_hz[a], 1.0, 0.05) << a << " " << b;
    ASSERT_NE(parity[a], 0);
    ASSERT_NE(parity[b], 0);
    EXPECT_EQ(parity[a] * parity[b], -1) << a << " " << b;
  }
}

// The authors' tree01 as a real branching tree: positive, sorted frequencies that do not move
// when every element is halved.
TEST(FemModes, AuthorsTree01IsStableToRefinement) {
  const Tree tree = ReadTreeFile(test::SharedData("authors-demo/tree_model/tree01.txt"));
  const WoodProperties wood = test::TestWood();
  const FemModel model(tree, wood, {.max_element_length_m = 0.1});
  const FemModel fine(tree, wood, {.max_element_length_m = 0.03});
  EXPECT_GT(fine.node_count(), model.node_count());
  const ModalBasis modes = ComputeModes(model, {.count = 10});
  const ModalBasis fine_modes = ComputeModes(fine, {.count = 10});
  ASSERT_EQ(modes.count(), 10);
  for (int i = 0; i < 10; ++i) {
    EXPECT_GT(modes.frequency_hz[i], 0.1) << i;
    EXPECT_LT(modes.frequency_hz[i], 100.0) << i;
    if (i > 0) {
      EXPECT_GE(modes.frequency_hz[i], modes.frequency_hz[i - 1]) << i;
    }
    EXPECT_NEAR(fine_modes.frequency_hz[i] / modes.frequency_hz[i], 1.0, 1e-3) << i;
  }
  ExpectMassOrthonormal(model, modes, 1e-7);
}

TEST(FemModes, BadOptionsAreInputErrors) {
  const FemModel model(test::YTree(), test::TestWood());
  EXPECT_THROW(ComputeModes(model, {.count = 0}), InputError);
  EXPECT_THROW(ComputeModes(model, {.count = 10, .max_count = 5}), InputError);
  EXPECT_THROW(ComputeModes(model, {.count = 4, .cover_frequency_hz = -1}), InputError);
  // More modes than degrees of freedom: all there are.
  const FemModel tiny(test::UniformCantilever({0, 0, 1}, 1.0, 0.02, 1), test::TestWood(),
                      {.max_element_length_m = 1.0});
  EXPECT_EQ(ComputeModes(tiny, {.count = 60}).count(), 6);
}

}  // namespace
}  // namespace simtree::synth
