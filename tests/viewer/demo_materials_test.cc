// A tree without materials gets the authors' per-level values, marked default; branches that
// have one keep it.

#include "simtree/viewer/demo_materials.h"

#include <gtest/gtest.h>

#include "simtree/core/legacy_format.h"
#include "viewer_fixtures.h"

namespace simtree::viewer {
namespace {

TEST(DemoMaterials, MatchTheAuthorsParameterFileLevelByLevel) {
  // tree01 with its tree_parameters.txt: every branch's material is its level's demo value.
  Tree tree = ReadLegacyTree(test::SharedData("authors-demo/tree_model/tree01.txt"));
  ReadLegacyParameters(test::SharedData("authors-demo/tree_parameters.txt"), tree);
  for (const Branch& b : tree.branches) {
    const Material demo = DemoLevelMaterial(b.level);
    EXPECT_DOUBLE_EQ(demo.modes[0].frequency_hz, b.material->modes[0].frequency_hz) << b.id;
    EXPECT_DOUBLE_EQ(demo.modes[0].damping_ratio, b.material->modes[0].damping_ratio) << b.id;
    EXPECT_DOUBLE_EQ(demo.stiffness, b.material->stiffness) << b.id;
    EXPECT_EQ(demo.source, MaterialSource::kDefault);
  }
}

TEST(DemoMaterials, FillOnlyWhatIsMissing) {
  Tree tree = test::ViewerTree();
  tree.branches[1].material.reset();
  tree.branches[3].material.reset();
  EXPECT_EQ(FillMissingMaterials(tree), 2);
  EXPECT_TRUE(tree.IsSimulationReady());
  EXPECT_EQ(tree.branches[0].material->source, MaterialSource::kMeasured);
  EXPECT_EQ(tree.branches[3].material->source, MaterialSource::kDefault);
  EXPECT_DOUBLE_EQ(tree.branches[3].material->modes[0].frequency_hz, 1.2);  // level 2
  EXPECT_EQ(FillMissingMaterials(tree), 0);
  EXPECT_DOUBLE_EQ(DemoLevelMaterial(9).stiffness, DemoLevelMaterial(4).stiffness);
}

}  // namespace
}  // namespace simtree::viewer
