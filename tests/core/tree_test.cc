#include "simtree/core/tree.h"

#include <gtest/gtest.h>

#include "core/tree_fixtures.h"
#include "simtree/core/units.h"

namespace simtree {
namespace {

TEST(Branch, LengthArcLengthsAndPointAt) {
  const Tree tree = test::SmallTree();
  const Branch& trunk = tree.trunk();
  EXPECT_NEAR(trunk.Length(), 1.0, 1e-12);
  const auto s = trunk.ArcLengths();
  ASSERT_EQ(s.size(), 5u);
  EXPECT_NEAR(s[2], 0.5, 1e-12);
  EXPECT_TRUE(trunk.PointAt(0.6).isApprox(Eigen::Vector3d(0, 0, 0.6)));
  EXPECT_TRUE(trunk.PointAt(-1).isApprox(Eigen::Vector3d(0, 0, 0)));
  EXPECT_TRUE(trunk.PointAt(9).isApprox(Eigen::Vector3d(0, 0, 1)));
}

TEST(Branch, VolumeOfAFrustumChain) {
  Branch b;
  b.nodes = {{{0, 0, 0}, 0.1}, {{0, 0, 1}, 0.1}};
  EXPECT_NEAR(b.Volume(), kPi * 0.01, 1e-12);
  b.nodes = {{{0, 0, 0}, 0.2}, {{0, 0, 3}, 1e-9}};  // a cone: pi r^2 h / 3
  EXPECT_NEAR(b.Volume(), kPi * 0.04, 1e-9);
}

TEST(Tree, ChildrenAndDepthFirstOrder) {
  const Tree tree = test::SmallTree();
  const auto children = tree.Children();
  EXPECT_EQ(children[0], (std::vector<int>{1, 2}));
  EXPECT_EQ(children[1], (std::vector<int>{3}));
  EXPECT_EQ(tree.DepthFirstOrder(), (std::vector<int>{0, 1, 3, 2}));
  EXPECT_EQ(tree.MaxLevel(), 2);
  EXPECT_EQ(tree.NodeCount(), 16);
}

TEST(Tree, BoundsIncludeRadii) {
  const Tree tree = test::SmallTree();
  Eigen::Vector3d lo, hi;
  tree.Bounds(&lo, &hi);
  EXPECT_NEAR(lo.z(), -0.1, 1e-12);  // trunk base radius below the base
  EXPECT_GT(hi.z(), 1.0);
}

TEST(Material, StiffnessMassAndFrequencyStayConsistent) {
  Material m = Material::FromFrequencyDampingStiffness(2.0, 0.03, 5000, MaterialSource::kDefault);
  EXPECT_NEAR(m.mass_kg, 5000 / (4 * kPi * kPi * 4.0), 1e-12);
  m.SetStiffness(2500);
  EXPECT_NEAR(m.mass_kg, 2500 / (4 * kPi * kPi * 4.0), 1e-12);
  EXPECT_DOUBLE_EQ(m.modes[0].frequency_hz, 2.0);
  m.SetFrequency(ModeKind::kBendU, 1.0);
  EXPECT_NEAR(m.stiffness, ModalStiffness(m.mass_kg, 1.0), 1e-9);
  m.SetFrequency(ModeKind::kTwistV, 4.0);  // another mode leaves k alone
  EXPECT_NEAR(m.stiffness, ModalStiffness(m.mass_kg, 1.0), 1e-9);
  EXPECT_EQ(m.mode(ModeKind::kTwistV).frequency_hz, 4.0);
}

}  // namespace
}  // namespace simtree
