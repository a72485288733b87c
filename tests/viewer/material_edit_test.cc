// Live material edits: k = 4 m pi^2 f^2 holds after each, the modes keep their ratios, a level
// edit reaches every branch of the level, the simulation uses the new values at once, and
// impossible values are refused.

#include "simtree/viewer/detail/material_edit.h"

#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/core/units.h"
#include "viewer_fixtures.h"

namespace simtree::viewer {
namespace {

Material Spread() {
  Material m = Material::FromFrequencyDampingStiffness(1.0, 0.02, 1000, MaterialSource::kMeasured);
  m.modes[1].frequency_hz = 1.1;
  m.modes[1].damping_ratio = 0.03;
  return m;
}

TEST(MaterialEdit, FrequencyKeepsMassAndRatios) {
  const Material m = Spread();
  const Material f = WithProperty(m, MaterialProperty::kFrequency, 2.0);
  EXPECT_DOUBLE_EQ(f.modes[0].frequency_hz, 2.0);
  EXPECT_NEAR(f.modes[1].frequency_hz, 2.2, 1e-12);
  EXPECT_NEAR(f.mass_kg, m.mass_kg, 1e-12);
  EXPECT_NEAR(f.stiffness, ModalStiffness(f.mass_kg, 2.0), 1e-9);
  EXPECT_NEAR(f.stiffness, 4000.0, 1e-9);
}

TEST(MaterialEdit, StiffnessKeepsFrequenciesAndDampingScales) {
  const Material m = Spread();
  const Material k = WithProperty(m, MaterialProperty::kStiffness, 250.0);
  EXPECT_DOUBLE_EQ(k.stiffness, 250.0);
  EXPECT_DOUBLE_EQ(k.modes[0].frequency_hz, 1.0);
  EXPECT_NEAR(k.mass_kg, ModalMass(250.0, 1.0), 1e-12);
  const Material d = WithProperty(m, MaterialProperty::kDamping, 0.04);
  EXPECT_DOUBLE_EQ(d.modes[0].damping_ratio, 0.04);
  EXPECT_NEAR(d.modes[1].damping_ratio, 0.06, 1e-12);
  EXPECT_DOUBLE_EQ(WithProperty(m, MaterialProperty::kDamping, 0.0).modes[1].damping_ratio, 0.0);
}

TEST(MaterialEdit, BadValuesAreRefused) {
  const Material m = Spread();
  EXPECT_THROW(WithProperty(m, MaterialProperty::kFrequency, 0.0), InputError);
  EXPECT_THROW(WithProperty(m, MaterialProperty::kStiffness, -5.0), InputError);
  EXPECT_THROW(WithProperty(m, MaterialProperty::kDamping, std::nan("")), InputError);
  EXPECT_THROW(ParseMaterialProperty("colour", "material"), InputError);
  EXPECT_EQ(ParseMaterialProperty("damping", "m"), MaterialProperty::kDamping);
  EXPECT_DOUBLE_EQ(RangeOf(MaterialProperty::kStiffness).max, 50000.0);
}

TEST(MaterialEdit, LevelEditsReachTheSimulationLive) {
  const Tree tree = test::ViewerTree();
  dynamics::TreeDynamics sim(tree);
  const auto level1 = BranchesOfLevel(tree, 1);
  EXPECT_EQ(level1, (std::vector<int>{1, 2}));
  EXPECT_EQ(EditMaterials(sim, level1, MaterialProperty::kFrequency, 3.0), 2);
  EXPECT_DOUBLE_EQ(sim.material(1).modes[0].frequency_hz, 3.0);
  EXPECT_DOUBLE_EQ(sim.material(2).modes[0].frequency_hz, 3.0);
  EXPECT_DOUBLE_EQ(sim.material(0).modes[0].frequency_hz, 1.0);
  EXPECT_THROW(EditMaterials(sim, {9}, MaterialProperty::kDamping, 0.1), InputError);
  // A branch that swings at its new frequency: a free decay of branch 3 crosses zero about
  // 2 f times a second.
  EditMaterials(sim, {3}, MaterialProperty::kFrequency, 4.0);
  EditMaterials(sim, {3}, MaterialProperty::kDamping, 0.0);
  dynamics::ModalState state;
  state.q = {0.01, 0, 0};
  sim.SetModalState(3, state);
  int crossings = 0;
  double last = sim.modal_state(3).q[0];
  for (int i = 0; i < 1000; ++i) {
    sim.Step(0.001);
    const double q = sim.modal_state(3).q[0];
    crossings += (q > 0) != (last > 0);
    last = q;
  }
  EXPECT_NEAR(crossings, 8, 1);
}

}  // namespace
}  // namespace simtree::viewer
