#include "simtree/identification/materials_file.h"

#include <cmath>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/identification/detail/test_signals.h"
#include "test_util.h"

namespace simtree::identification {
namespace {

using ::testing::HasSubstr;

IdentificationResult Identified() {
  SyntheticMarkerTree tree;
  tree.links.resize(2);
  tree.links[0].theta_u = {{1.2, 0.03, 0.1, 0.0}};
  tree.links[0].theta_w = {{1.4, 0.04, 0.06, 0.0}};
  tree.links[1].parent = 0;
  tree.links[1].rest_direction = {1, -0.2, 0};
  tree.links[1].theta_u = {{1.6, 0.05, 0.1, 0.0}};
  std::vector<MarkerLink> markers;
  const Trajectories t = MakeMarkerTrajectories(tree, 30, 0, 10, &markers);
  markers[1].branch = 3;
  markers[2].branch = 3;               // two links on one branch: the surer one is kept
  markers.push_back({7, "M7", 2, 4});  // no trajectory
  return IdentifyMaterials(t, markers);
}

TEST(MaterialsFile, FromAnIdentificationWithBranchModesAndAMissingLink) {
  const MaterialsFile m = MaterialsFromIdentification(Identified(), "t.csv");
  EXPECT_EQ(m.estimator, EstimatorKind::kDampedSinusoidFit);
  ASSERT_EQ(m.links.size(), 4u);
  EXPECT_EQ(m.links[3].value.status, EstimateStatus::kMissingMarker);
  ASSERT_EQ(m.branches.size(), 1u);  // branch 4's link has no value, the root has no branch
  const BranchMaterial& b = m.branches[0];
  EXPECT_EQ(b.branch, 3);
  EXPECT_FALSE(b.assumed[0]);
  EXPECT_TRUE(b.assumed[2]);
  const LinkMaterial& chosen = b.link_child == 1 ? m.links[1] : m.links[2];
  EXPECT_DOUBLE_EQ(b.modes[2].frequency_hz, chosen.value.frequency_hz);
  EXPECT_DOUBLE_EQ(b.modes[0].frequency_hz, chosen.planes[0].frequency_hz);
  EXPECT_EQ(m.ranges.measured, 2);  // the root marker does not move: flat
}

// A link's branch mode, when it has one, is what its branch gets (all three modes here).
TEST(MaterialsFile, ABranchTakesItsLinksBranchMode) {
  MaterialsFile m = MaterialsFromIdentification(Identified(), "t.csv");
  for (LinkMaterial& l : m.links) {
    if (l.child != 1 && l.child != 2) continue;
    l.branch_mode = l.value;
    l.branch_mode.frequency_hz = 2.5;
    l.branch_mode.damping_ratio = 0.05;
    l.branch_planes = {l.branch_mode, l.branch_mode};
  }
  AssignBranchMaterials(m);
  ASSERT_EQ(m.branches.size(), 1u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_DOUBLE_EQ(m.branches[0].modes[k].frequency_hz, 2.5);
    EXPECT_DOUBLE_EQ(m.branches[0].modes[k].damping_ratio, 0.05);
  }
}

TEST(MaterialsFile, JsonRoundTripWritesNullForWhatWasNotEstimatedOrUnresolved) {
  const MaterialsFile m = MaterialsFromIdentification(Identified(), "t.csv");
  const nlohmann::ordered_json j = MaterialsToJson(m);
  EXPECT_TRUE(j["links"][3]["frequency_hz"].is_null());
  EXPECT_EQ(j["links"][3]["status"], "missing_marker");
  EXPECT_EQ(j["links"][1]["estimators"].size(), 3u);
  // Which poles the fit's value was read on, and why; none for a link without a value.
  EXPECT_THAT(j["links"][1]["poles"]["used"].get<std::string>(), ::testing::AnyOf("shared", "own"));
  EXPECT_THAT(j["links"][1]["poles"]["why"].get<std::string>(), HasSubstr("BIC"));
  EXPECT_TRUE(j["links"][3]["poles"].is_null());
  // The joint poles as the link carries them, and the mode its branch gets (by default the
  // dominant one) with the most participating pole beside it; read back below.
  ASSERT_FALSE(j["links"][1]["modes"].empty());
  EXPECT_TRUE(j["links"][1]["modes"][0].contains("participation"));
  EXPECT_DOUBLE_EQ(j["links"][1]["branch_mode"]["frequency_hz"].get<double>(),
                   m.links[1].value.frequency_hz);
  EXPECT_FALSE(j["links"][3].contains("branch_mode"));
  const auto dir = test::TempDir();
  WriteMaterialsJson(m, dir / "m.json");
  const MaterialsFile back = ReadMaterialsJson(dir / "m.json");
  EXPECT_EQ(MaterialsToJson(back).dump(), j.dump());

  // A fit's standard deviation it cannot give (a pole it cannot resolve) is infinite: null in the
  // file and infinite again when read, so the reader's summary leaves the link out as the
  // writer's did; a spectral estimator's null stays "no uncertainty given" (NaN).
  MaterialsFile unresolved = m;
  LinkMaterial& link = unresolved.links[2];
  ASSERT_EQ(link.value.status, EstimateStatus::kOk);
  link.value.frequency_std_hz = link.value.damping_std = std::numeric_limits<double>::infinity();
  WriteMaterialsJson(unresolved, dir / "unresolved.json");
  const MaterialsFile read = ReadMaterialsJson(dir / "unresolved.json");
  EXPECT_TRUE(std::isinf(read.links[2].value.frequency_std_hz));
  EXPECT_TRUE(std::isinf(read.links[2].value.damping_std));
  EXPECT_THAT(read.ranges.uncertain, ::testing::Contains(link.label));
  for (const auto& [kind, e] : read.links[1].estimators) {
    if (kind == EstimatorKind::kHalfPowerFft) {
      EXPECT_TRUE(std::isnan(e.frequency_std_hz));
    }
  }
}

// The summary's ranges leave out a value the fit is unsure of; a reader recomputes them alike.
TEST(MaterialsFile, SummaryListsUncertainLinksAndReadsBackTheSame) {
  MaterialsFile m = MaterialsFromIdentification(Identified(), "t.csv");
  LinkMaterial& unsure = m.links[1];
  ASSERT_EQ(unsure.value.status, EstimateStatus::kOk);
  unsure.value.damping_ratio = 0.5;
  unsure.value.damping_std = 0.2;  // 40%
  const auto dir = test::TempDir();
  WriteMaterialsJson(m, dir / "m.json");
  const MaterialsFile back = ReadMaterialsJson(dir / "m.json");
  EXPECT_EQ(back.ranges.uncertain, std::vector<std::string>{unsure.label});
  EXPECT_EQ(back.ranges.damping_count, 1);
  EXPECT_LT(back.ranges.max_damping, 0.1);
  EXPECT_DOUBLE_EQ(back.ranges.all_max_damping, 0.5);
  const nlohmann::ordered_json summary = MaterialsToJson(back)["summary"];
  EXPECT_EQ(summary["uncertain"][0], unsure.label);
  EXPECT_DOUBLE_EQ(summary["max_relative_std"]["damping"].get<double>(), 0.2);
}

TEST(MaterialsFile, BadFilesNameTheField) {
  const nlohmann::json good = MaterialsToJson(MaterialsFromIdentification(Identified(), "t.csv"));
  struct Case {
    const char* name;
    std::function<void(nlohmann::json&)> edit;
    const char* expected;
  };
  const std::vector<Case> cases = {
      {"format", [](auto& j) { j["format"] = "simtree.tree"; }, "expected \"simtree.materials\""},
      {"ok without value", [](auto& j) { j["links"][1]["frequency_hz"] = nullptr; },
       "links[1]: status \"ok\" needs a frequency_hz"},
      {"negative damping", [](auto& j) { j["links"][1]["damping_ratio"] = -0.1; },
       "links[1].damping_ratio: expected in (0, 1)"},
      {"status", [](auto& j) { j["links"][0]["status"] = "great"; }, "unknown status"},
      {"pole frequency", [](auto& j) { j["links"][1]["modes"][0]["frequency_hz"] = -1.0; },
       "links[1].modes[0].frequency_hz: expected > 0"},
      {"estimator", [](auto& j) { j["estimator"] = "x"; }, "estimator: unknown estimator"},
      {"modes", [](auto& j) { j["branches"][0]["modes"].erase(0); }, "expected 3 modes"},
      {"mode order",
       [](auto& j) { std::swap(j["branches"][0]["modes"][0], j["branches"][0]["modes"][1]); },
       "expected the order bend_u, bend_w, twist_v"},
  };
  for (const Case& c : cases) {
    nlohmann::json j = good;
    c.edit(j);
    try {
      MaterialsFromJson(j, "bad.json");
      ADD_FAILURE() << c.name;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr("bad.json")) << c.name;
      EXPECT_THAT(e.what(), HasSubstr(c.expected)) << c.name;
    }
  }
}

}  // namespace
}  // namespace simtree::identification
