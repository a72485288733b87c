#include "simtree/core/validate.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/tree_fixtures.h"
#include "simtree/core/error.h"

namespace simtree {
namespace {

using ::testing::HasSubstr;

std::string FirstProblem(const Tree& tree, const ValidationOptions& options = {}) {
  const auto problems = FindProblems(tree, options);
  return problems.empty() ? "" : problems.front().where + ": " + problems.front().message;
}

TEST(Validate, AcceptsAWellFormedTree) {
  EXPECT_EQ(FirstProblem(test::SmallTreeWithMaterials()), "");
  ValidationOptions strict;
  strict.require_materials = true;
  EXPECT_EQ(FirstProblem(test::SmallTreeWithMaterials(), strict), "");
  EXPECT_THAT(FirstProblem(test::SmallTree(), strict), HasSubstr("branches[0].material"));
}

TEST(Validate, NamesTheFieldAndWhatWasExpected) {
  Tree t = test::SmallTree();
  t.branches[2].nodes[1].radius = -0.1;
  EXPECT_EQ(FirstProblem(t), "branches[2].nodes[1].radius: expected a positive radius, got -0.1");

  t = test::SmallTree();
  t.branches[1].nodes[2].position.x() = std::nan("");
  EXPECT_THAT(FirstProblem(t), HasSubstr("branches[1].nodes[2].position: expected finite"));

  t = test::SmallTree();
  t.branches[3].parent_node = 9;
  EXPECT_THAT(FirstProblem(t),
              HasSubstr("branches[3].parent_node: expected a node index in [0, 3] of parent "
                        "branch 1, got 9"));

  t = test::SmallTree();
  t.branches[3].nodes[0].position.x() += 0.01;
  EXPECT_THAT(FirstProblem(t), HasSubstr("branches[3].nodes[0]: expected to start on node 3"));

  t = test::SmallTree();
  t.branches[1].parent = 3;  // child before parent
  EXPECT_THAT(FirstProblem(t), HasSubstr("branches[1].parent: expected a parent id in [0, 0]"));

  t = test::SmallTree();
  t.branches[2].level = 5;
  EXPECT_THAT(FirstProblem(t), HasSubstr("branches[2].level: expected 1"));

  t = test::SmallTree();
  t.branches[2].frame.w = -t.branches[2].frame.w;  // left-handed
  EXPECT_THAT(FirstProblem(t), HasSubstr("branches[2].frame: expected a right-handed"));

  t = test::SmallTree();
  t.branches[0].nodes.resize(1);
  EXPECT_THAT(FirstProblem(t), HasSubstr("branches[0].nodes: expected at least 2 nodes"));

  EXPECT_THAT(FirstProblem(Tree{}), HasSubstr("expected at least one branch"));
}

TEST(Validate, MaterialRanges) {
  Tree t = test::SmallTreeWithMaterials();
  t.branches[1].material->modes[2].frequency_hz = 0.0;
  EXPECT_THAT(FirstProblem(t), HasSubstr("branches[1].material.modes[2].frequency_hz: expected a "
                                         "frequency in [0.01, 200] Hz, got 0"));
  t = test::SmallTreeWithMaterials();
  t.branches[1].material->modes[0].damping_ratio = std::nan("");
  EXPECT_THAT(FirstProblem(t), HasSubstr("modes[0].damping_ratio: expected a damping ratio"));
  t = test::SmallTreeWithMaterials();
  t.branches[1].material->stiffness *= 2;
  EXPECT_THAT(FirstProblem(t), HasSubstr("material.stiffness: expected 4 m pi^2 f^2"));
  t = test::SmallTreeWithMaterials();
  t.branches[1].material->modes[1].kind = ModeKind::kBendU;
  EXPECT_THAT(FirstProblem(t), HasSubstr("modes[1].kind: expected \"bend_w\""));
}

TEST(Validate, Markers) {
  Tree t = test::SmallTreeWithMaterials();
  t.markers[1].branch = 9;
  EXPECT_THAT(FirstProblem(t), HasSubstr("markers[1].branch: expected a branch id in [0, 3]"));
  t = test::SmallTreeWithMaterials();
  t.markers[0].arc_length = 5.0;
  EXPECT_THAT(FirstProblem(t), HasSubstr("markers[0].arc_length"));
  t = test::SmallTreeWithMaterials();
  t.markers[1].parent = 1;
  EXPECT_THAT(FirstProblem(t), HasSubstr("markers[1].parent"));
}

// Marker ids are the tracker's: a marker never seen leaves a gap, which is fine; a repeated or
// negative id, or a parent that is not on the tree, is not.
TEST(Validate, MarkerIdsAreUniqueNotConsecutive) {
  Tree t = test::SmallTreeWithMaterials();
  ASSERT_GE(t.markers.size(), 2u);
  t.markers.back().id = 7;
  EXPECT_TRUE(FindProblems(t).empty()) << FirstProblem(t);
  t.markers.back().id = t.markers.front().id;
  EXPECT_THAT(FirstProblem(t), HasSubstr("appears twice"));
  t.markers.back().id = -2;
  EXPECT_THAT(FirstProblem(t), HasSubstr("expected an id >= 0"));
  t = test::SmallTreeWithMaterials();
  t.markers.back().parent = 42;
  EXPECT_THAT(FirstProblem(t), HasSubstr(".parent: expected -1 or the id of another marker"));
}

TEST(Validate, ThrowsInputErrorWithSourceAndCount) {
  Tree t = test::SmallTree();
  t.branches[2].nodes[1].radius = -0.1;
  t.branches[2].nodes[2].radius = -0.1;
  try {
    Validate(t, "tree.json");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "tree.json: branches[2].nodes[1].radius: expected a positive radius, got -0.1 (and 1 "
              "more problems)");
  }
}

}  // namespace
}  // namespace simtree
