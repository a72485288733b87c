#include "simtree/simready/build.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "identification/tree_fixture.h"
#include "simtree/core/error.h"
#include "simtree/core/option_checks.h"
#include "simtree/core/tree_json.h"
#include "simtree/core/units.h"
#include "simtree/core/validate.h"

namespace simtree::simready {
namespace {

using ::testing::HasSubstr;

TEST(SimulationReady, CantileverModeShapeIsTipNormalisedWithAQuarterModalMass) {
  EXPECT_NEAR(CantileverModeShape(0.0), 0.0, 1e-12);
  EXPECT_NEAR(CantileverModeShape(1.0), 1.0, 1e-12);
  // Clamped: zero slope at the root, so phi grows like xi^2 there.
  EXPECT_NEAR(CantileverModeShape(1e-3) / CantileverModeShape(2e-3), 0.25, 1e-3);
  double integral = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) integral += std::pow(CantileverModeShape((i + 0.5) / n), 2) / n;
  EXPECT_NEAR(integral, 0.25, 1e-6);  // the known modal mass of a uniform cantilever
}

TEST(SimulationReady, ModalMassOfAUniformBranchAndOfOneCarryingAnother) {
  Tree tree;
  tree.branches.push_back(test::StraightBranch(0, -1, 0, {0, 0, 0}, {0, 0, 1}, 2.0, 0.05, 0.05, 9));
  AssignLevels(tree);
  const double rho = 800, mass = rho * kPi * 0.05 * 0.05 * 2.0;
  EXPECT_NEAR(BranchModalMass(tree, 0, rho), 0.25 * mass, 1e-3 * mass);
  // A child at the tip adds its whole mass (phi = 1 there); at mid-length, phi(0.5)^2 of it.
  tree.branches.push_back(test::StraightBranch(1, 0, 8, {0, 0, 2}, {1, 0, 0}, 1.0, 0.02, 0.02));
  tree.branches.push_back(test::StraightBranch(2, 0, 4, {0, 0, 1}, {0, 1, 0}, 1.0, 0.02, 0.02));
  AssignLevels(tree);
  const std::vector<double> subtree = SubtreeMasses(tree, rho);
  const double child = rho * kPi * 0.02 * 0.02 * 1.0;
  EXPECT_NEAR(subtree[0], mass + 2 * child, 1e-9 * mass);
  EXPECT_NEAR(BranchModalMass(tree, 0, rho, subtree),
              0.25 * mass + child + child * std::pow(CantileverModeShape(0.5), 2), 1e-3 * mass);
}

identification::MaterialsFile Measured(std::vector<std::pair<int, double>> branch_frequency) {
  identification::MaterialsFile m;
  for (auto [branch, f] : branch_frequency) {
    identification::BranchMaterial b;
    b.branch = branch;
    b.modes = {Mode{ModeKind::kBendU, 0.95 * f, 0.036}, Mode{ModeKind::kBendW, 1.05 * f, 0.024},
               Mode{ModeKind::kTwistV, f, 0.03}};
    m.branches.push_back(b);
  }
  return m;
}

TEST(SimulationReady, MeasuredBranchesKeepTheirValuesOthersAreInterpolatedAndMarked) {
  const Tree tree = test::IdentificationTree();
  BuildReport report;
  BuildOptions options;
  options.wood_density_kg_m3 = 850;
  const Tree ready =
      BuildSimulationReadyTree(tree, Measured({{0, 1.0}, {1, 1.2}, {4, 1.4}}), options, &report);
  EXPECT_TRUE(ready.IsSimulationReady());
  EXPECT_TRUE(FindProblems(ready, {.require_materials = true}).empty());
  EXPECT_EQ(report.measured, 3);
  EXPECT_EQ(report.interpolated, 3);
  const Material& m1 = *ready.branches[1].material;
  EXPECT_EQ(m1.source, MaterialSource::kMeasured);
  EXPECT_DOUBLE_EQ(m1.modes[0].frequency_hz, 0.95 * 1.2);
  EXPECT_DOUBLE_EQ(m1.modes[1].damping_ratio, 0.024);
  for (int b : {2, 3, 5}) {
    const Material& m = *ready.branches[b].material;
    EXPECT_EQ(m.source, MaterialSource::kInterpolated) << b;
    // Inside the measured range, the three modes in the measured branches' proportions.
    EXPECT_GE(m.modes[2].frequency_hz, 1.0 - 1e-9);
    EXPECT_LE(m.modes[2].frequency_hz, 1.4 + 1e-9);
    EXPECT_NEAR(m.modes[0].frequency_hz / m.modes[2].frequency_hz, 0.95, 1e-9);
    EXPECT_NEAR(m.modes[1].damping_ratio / m.modes[2].damping_ratio, 0.8, 1e-9);
  }
  for (const Branch& b : ready.branches) {
    const Material& m = *b.material;
    EXPECT_NEAR(m.mass_kg, BranchModalMass(ready, b.id, 850, SubtreeMasses(ready, 850)), 1e-12);
    EXPECT_NEAR(m.stiffness, 4 * m.mass_kg * kPi * kPi * std::pow(m.modes[0].frequency_hz, 2),
                1e-9 * m.stiffness);
  }
  EXPECT_NEAR(report.total_mass_kg, SubtreeMasses(tree, 850)[0], 1e-9);
}

TEST(SimulationReady, LinksWithoutBranchesUseTheStaticTreesMarkers) {
  Tree tree = test::IdentificationTree();
  tree.markers.push_back({0, "M0", 2, 0.4, -1, tree.branches[2].PointAt(0.4)});
  identification::MaterialsFile m;
  identification::LinkMaterial link;
  link.child = 0;
  link.value.frequency_hz = 1.3;
  link.value.damping_ratio = 0.04;
  link.planes = {link.value, link.value};
  m.links.push_back(link);
  const Tree ready = BuildSimulationReadyTree(tree, m);
  EXPECT_EQ(ready.branches[2].material->source, MaterialSource::kMeasured);
  EXPECT_DOUBLE_EQ(ready.branches[2].material->modes[0].frequency_hz, 1.3);
  EXPECT_DOUBLE_EQ(ready.branches[0].material->modes[0].frequency_hz, 1.3);
}

TEST(SimulationReady, NothingMeasuredOrBranchesTheTreeLacksAreErrors) {
  const Tree tree = test::IdentificationTree();
  EXPECT_THAT([&] { BuildSimulationReadyTree(tree, identification::MaterialsFile{}); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("no link has a measured value")));
  EXPECT_THAT(
      [&] {
        BuildSimulationReadyTree(tree, Measured({{9, 1.0}}));
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("branch 9 is not in the tree")));
  identification::MaterialsFile unplaced;
  identification::LinkMaterial link;
  link.child = 3;
  link.value.frequency_hz = 1.0;
  link.value.damping_ratio = 0.03;
  unplaced.links.push_back(link);
  EXPECT_THAT([&] { BuildSimulationReadyTree(tree, unplaced); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("none is on a known branch")));
}

TEST(SimulationReady, OptionsOutOfRangeNameTheField) {
  const Tree tree = test::IdentificationTree();
  auto error = [&](const BuildOptions& options) {
    try {
      BuildSimulationReadyTree(tree, Measured({{1, 1.2}, {2, 1.4}}), options);
    } catch (const InputError& e) {
      return e.where();
    }
    return std::string("no error");
  };
  BuildOptions density;
  density.wood_density_kg_m3 = -900;
  EXPECT_EQ(error(density), "wood_density_kg_m3");
  BuildOptions cantilever;
  cantilever.interpolation.min_branches_cantilever = 1;
  EXPECT_EQ(error(cantilever), "interpolation.min_branches_cantilever");
  BuildOptions two_slopes;
  two_slopes.interpolation.min_branches_two_slopes = 0;
  EXPECT_EQ(error(two_slopes), "interpolation.min_branches_two_slopes");
  BuildOptions z;
  z.uncertainty.max_z = 0;
  EXPECT_EQ(error(z), "uncertainty.max_z");
  EXPECT_THAT([] { InterpolationOptions{.min_branches_cantilever = 2}.Validate(); },
              ::testing::ThrowsMessage<InputError>(
                  HasSubstr("options: min_branches_cantilever: expected >= 3, got 2")));
}

TEST(SimulationReady, DepthFirstRenumberingKeepsTheHierarchy) {
  Tree tree = test::IdentificationTree();
  tree.markers.push_back({0, "M0", 4, 0.1, -1, tree.branches[4].PointAt(0.1)});
  std::vector<int> new_id;
  const Tree renumbered = RenumberDepthFirst(tree, &new_id);
  // Depth-first: 0, 1, 4, 2, 5, 3.
  EXPECT_EQ(new_id, (std::vector<int>{0, 1, 3, 5, 2, 4}));
  EXPECT_EQ(renumbered.branches[2].parent, 1);
  EXPECT_EQ(renumbered.markers[0].branch, 2);
  EXPECT_TRUE(FindProblems(renumbered).empty());
  for (int old = 0; old < tree.size(); ++old) {
    EXPECT_EQ(renumbered.branches[new_id[old]].nodes.front().position,
              tree.branches[old].nodes.front().position);
  }
}

TEST(SimulationReady, ATreeWithoutAPullTestGetsItsSpeciesTypicalValuesMarkedAssumed) {
  const Tree tree = test::IdentificationTree();
  BuildReport report;
  const Tree ready =
      BuildAssumedSimulationReadyTree(tree, AssumedMaterialOf("Magnolia"), {}, &report);
  EXPECT_TRUE(FindProblems(ready, {.require_materials = true}).empty());
  EXPECT_EQ(report.assumed, tree.size());
  EXPECT_EQ(report.measured, 0);
  // Magnolia in Table IV: 0.72-1.19 Hz, damping 0.023-0.033; the middle on every mode.
  for (const Branch& b : ready.branches) {
    const Material& m = *b.material;
    EXPECT_EQ(m.source, MaterialSource::kAssumed);
    for (const Mode& mode : m.modes) {
      EXPECT_DOUBLE_EQ(mode.frequency_hz, 0.955);
      EXPECT_DOUBLE_EQ(mode.damping_ratio, 0.028);
    }
    // Masses from the wood as for a measured tree; k follows f and the mass (paper Eq. 6).
    EXPECT_GT(m.mass_kg, 0.0);
    EXPECT_NEAR(m.stiffness, ModalStiffness(m.mass_kg, 0.955), 1e-9 * m.stiffness);
  }
  EXPECT_NEAR(report.total_mass_kg, SubtreeMasses(tree, BuildOptions{}.wood_density_kg_m3)[0],
              1e-9);
}

TEST(SimulationReady, AssumedValuesAreCheckedAndUnknownSpeciesListTheKnownOnes) {
  const Tree tree = test::IdentificationTree();
  EXPECT_THAT([] { AssumedMaterialOf("oak"); },
              ::testing::ThrowsMessage<InputError>(
                  HasSubstr("known species are acer_palmatum, magnolia, acer_rubrum")));
  EXPECT_DOUBLE_EQ(AssumedMaterialOf("acer-rubrum").frequency_hz, 0.5 * (0.93 + 1.50));
  auto error = [&](AssumedMaterial assumed) {
    try {
      BuildAssumedSimulationReadyTree(tree, assumed);
    } catch (const OptionError& e) {
      return e.field();
    }
    return std::string("none");
  };
  EXPECT_EQ(error({1.2, 0.03, "ok"}), "none");
  EXPECT_EQ(error({0.0, 0.03, ""}), "assumed.frequency_hz");
  EXPECT_EQ(error({std::nan(""), 0.03, ""}), "assumed.frequency_hz");
  EXPECT_EQ(error({1.2, 0.0, ""}), "assumed.damping_ratio");
  EXPECT_EQ(error({1.2, 1.5, ""}), "assumed.damping_ratio");
  EXPECT_THAT(
      [] {
        BuildAssumedSimulationReadyTree(Tree{}, {1.2, 0.03, ""});
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("no branches")));
}

}  // namespace
}  // namespace simtree::simready

namespace simtree::simready {
namespace {

// Five branches read at 1.2 Hz to 0.5%, and branch 4 read badly (a link tracked with many gaps
// reads noise: 0.41 Hz, damping 0.21, sd 0.3 Hz).
identification::MaterialsFile WithOneBadlyRead() {
  identification::MaterialsFile m =
      Measured({{0, 1.18}, {1, 1.2}, {2, 1.22}, {3, 1.21}, {5, 1.19}, {4, 0.41}});
  for (identification::BranchMaterial& b : m.branches) {
    b.frequency_std_hz = 0.005 * b.modes[2].frequency_hz;
    b.damping_std = 0.1 * b.modes[2].damping_ratio;
  }
  identification::BranchMaterial& bad = m.branches.back();
  bad.modes[2].damping_ratio = 0.21;
  bad.frequency_std_hz = 0.3;
  bad.damping_std = 0.2;
  return m;
}

TEST(SimulationReady, AValueWithAHugeDeviationIsFlaggedAndGetsTheInterpolatedValue) {
  const Tree tree = test::IdentificationTree();
  BuildReport report;
  const Tree ready = BuildSimulationReadyTree(tree, WithOneBadlyRead(), {}, &report);
  EXPECT_EQ(report.flagged, 1);
  EXPECT_EQ(report.replaced, 1);
  EXPECT_EQ(report.measured, 5);
  EXPECT_EQ(report.interpolated, 1);
  ASSERT_EQ(report.flagged_why.size(), 1u);
  EXPECT_THAT(report.flagged_why[0], HasSubstr("branch 4"));
  const Material& m4 = *ready.branches[4].material;
  EXPECT_EQ(m4.source, MaterialSource::kInterpolated);
  EXPECT_THAT(m4.uncertain, HasSubstr("frequency sd 73.2% of its value (over 10%)"));
  EXPECT_THAT(m4.uncertain, HasSubstr("replaced by the interpolation"));
  // The interpolation of the five trusted branches, which it was not fitted on.
  EXPECT_NEAR(m4.modes[2].frequency_hz, report.interpolation.Frequency(ready, 4), 1e-12);
  EXPECT_GE(m4.modes[2].frequency_hz, 1.18);
  // Its damping ratio is the interpolation's too; its own still counts there (by default only
  // frequencies are judged).
  EXPECT_NEAR(m4.modes[2].damping_ratio, report.interpolation.Damping(2), 1e-12);
  EXPECT_EQ(report.interpolation.measured, 5);
  EXPECT_DOUBLE_EQ(report.interpolation.min_frequency_hz, 1.18);
  for (int b : {0, 1, 2, 3, 5}) {
    EXPECT_EQ(ready.branches[b].material->source, MaterialSource::kMeasured) << b;
    EXPECT_TRUE(ready.branches[b].material->uncertain.empty()) << b;
  }
  // The note is written in tree JSON and read back; a file without it reads as not flagged.
  const Tree back = TreeFromJson(TreeToJson(ready), "ready.json");
  EXPECT_EQ(back.branches[4].material->uncertain, m4.uncertain);
  EXPECT_TRUE(back.branches[0].material->uncertain.empty());
  EXPECT_FALSE(TreeToJson(ready)["branches"][0]["material"].contains("uncertain"));
}

TEST(SimulationReady, KeepUncertainKeepsTheValueFlaggedAndTrustAllFlagsNone) {
  const Tree tree = test::IdentificationTree();
  BuildOptions keep;
  keep.uncertainty.replace = false;
  BuildReport report;
  const Tree kept = BuildSimulationReadyTree(tree, WithOneBadlyRead(), keep, &report);
  EXPECT_EQ(report.flagged, 1);
  EXPECT_EQ(report.replaced, 0);
  EXPECT_EQ(report.measured, 6);
  const Material& m4 = *kept.branches[4].material;
  EXPECT_EQ(m4.source, MaterialSource::kMeasured);
  EXPECT_DOUBLE_EQ(m4.modes[2].frequency_hz, 0.41);
  EXPECT_THAT(m4.uncertain, HasSubstr("kept"));
  // Flagged values stay out of the interpolation's fit either way.
  EXPECT_EQ(report.interpolation.measured, 5);

  BuildOptions trust;
  trust.uncertainty.flag = false;
  const Tree trusted = BuildSimulationReadyTree(tree, WithOneBadlyRead(), trust, &report);
  EXPECT_EQ(report.flagged, 0);
  EXPECT_EQ(report.interpolation.measured, 6);
  EXPECT_DOUBLE_EQ(trusted.branches[4].material->modes[2].frequency_hz, 0.41);
  EXPECT_TRUE(trusted.branches[4].material->uncertain.empty());
}

TEST(SimulationReady, AnUncertainDampingRatioAloneTakesTheInterpolatedDamping) {
  const Tree tree = test::IdentificationTree();
  identification::MaterialsFile m = WithOneBadlyRead();
  m.branches.back().modes[2].frequency_hz = 1.2;
  m.branches.back().frequency_std_hz = 0.006;  // the frequency known, the damping not (95%)
  BuildOptions damping;
  damping.uncertainty.max_damping_relative_std = 0.5;  // off by default
  BuildReport report;
  const Tree ready = BuildSimulationReadyTree(tree, m, damping, &report);
  EXPECT_EQ(report.flagged, 1);
  EXPECT_EQ(report.replaced, 0);
  const Material& m4 = *ready.branches[4].material;
  EXPECT_EQ(m4.source, MaterialSource::kMeasured);
  EXPECT_DOUBLE_EQ(m4.modes[2].frequency_hz, 1.2);
  EXPECT_NEAR(m4.modes[2].damping_ratio, 0.03, 1e-12);  // the others' damping
  EXPECT_THAT(m4.uncertain, HasSubstr("damping replaced by the interpolation"));
}

TEST(SimulationReady, AConfidentValueFarFromTheOthersIsFlaggedByItsZScore) {
  const Tree tree = test::IdentificationTree();
  identification::MaterialsFile m = WithOneBadlyRead();
  m.branches.back().frequency_std_hz = 0.002;  // 0.41 Hz to 0.5%, yet 1.2 Hz all around
  m.branches.back().damping_std = 0.01;
  BuildReport report;
  BuildOptions z_score;
  z_score.uncertainty.max_z = 3;  // off by default
  const Tree ready = BuildSimulationReadyTree(tree, m, z_score, &report);
  EXPECT_EQ(report.flagged, 1);
  EXPECT_THAT(ready.branches[4].material->uncertain, HasSubstr("sd from the"));
  EXPECT_EQ(ready.branches[4].material->source, MaterialSource::kInterpolated);
  BuildSimulationReadyTree(tree, m, {}, &report);
  EXPECT_EQ(report.flagged, 0);
  // A value without a deviation among values with one: its fit's covariance broke down.
  m = WithOneBadlyRead();
  m.branches.back().modes[2].frequency_hz = 1.2;
  m.branches.back().frequency_std_hz = kNaN;
  BuildSimulationReadyTree(tree, m, {}, &report);
  ASSERT_EQ(report.flagged, 1);
  EXPECT_THAT(report.flagged_why[0], HasSubstr("frequency sd unknown"));
}

}  // namespace
}  // namespace simtree::simready
