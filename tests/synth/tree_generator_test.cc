#include "simtree/synth/detail/tree_generator.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "simtree/core/error.h"
#include "simtree/core/frames.h"
#include "simtree/core/tree_json.h"
#include "simtree/core/units.h"
#include "simtree/core/validate.h"
#include "simtree/synth/detail/segment_grid.h"
#include "test_util.h"

namespace simtree::synth {
namespace {

using Vec3 = Eigen::Vector3d;

// Unit tangent at node i of a branch: the bisector of the adjacent segments (the generator's
// definition of "the parent's tangent at the attachment").
Vec3 Tangent(const Branch& b, size_t i) {
  Vec3 t = Vec3::Zero();
  if (i > 0) t += (b.nodes[i].position - b.nodes[i - 1].position).normalized();
  if (i + 1 < b.nodes.size()) t += (b.nodes[i + 1].position - b.nodes[i].position).normalized();
  return t.normalized();
}

Vec3 FirstDirection(const Branch& b) {
  return (b.nodes[1].position - b.nodes[0].position).normalized();
}

double AngleDeg(const Vec3& a, const Vec3& b) {
  return RadToDeg(std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)));
}

// A child's direction projected across its parent's tangent at the attachment.
Vec3 Across(const Tree& tree, const Branch& child) {
  const Vec3 t = Tangent(tree.branches[child.parent], child.parent_node);
  const Vec3 d = FirstDirection(child);
  return (d - d.dot(t) * t).normalized();
}

bool IsForkStem(const Tree& tree, const SpeciesParams& p, const Branch& b) {
  return b.parent == 0 && p.trunk.fork_count >= 2 &&
         b.parent_node == static_cast<int>(tree.trunk().nodes.size()) - 1;
}

// The lowest node of any branch but the trunk (which starts on the ground).
double LowestNodeOffTheTrunk(const Tree& tree) {
  double lowest = 1e9;
  for (const Branch& b : tree.branches) {
    if (b.is_trunk()) continue;
    for (const Node& n : b.nodes) lowest = std::min(lowest, n.position.z());
  }
  return lowest;
}

struct Case {
  std::string species;
  uint64_t seed;
};

class EveryPreset : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    species_ = SpeciesPreset(GetParam().species);
    result_ = GrowTree(species_, GetParam().seed);
  }
  const Tree& tree() const { return result_.tree; }
  SpeciesParams species_;
  TreeGenerationResult result_;
};

TEST_P(EveryPreset, IsAValidTreeOfTheRightSize) {
  EXPECT_TRUE(FindProblems(tree()).empty());
  EXPECT_EQ(tree().metadata.species, species_.name);
  EXPECT_EQ(tree().metadata.source,
            "synth " + species_.name + " seed " + std::to_string(GetParam().seed));
  EXPECT_TRUE(tree().markers.empty());
  for (const Branch& b : tree().branches) EXPECT_FALSE(b.material.has_value());
  // Trunk from the origin, up.
  EXPECT_EQ(tree().trunk().base().position, Vec3::Zero());
  EXPECT_GT(BranchAxis(tree().trunk()).z(), std::cos(DegToRad(species_.trunk.lean_deg + 10)));
  // Height: exactly the drawn one, in the species' range (2.5-4.5 m for the presets).
  double top = 0.0;
  for (const Branch& b : tree().branches) {
    for (const Node& n : b.nodes) top = std::max(top, n.position.z());
  }
  EXPECT_NEAR(top, result_.height_m, 1e-9);
  EXPECT_GE(top, species_.height_m * (1 - species_.height_spread) - 1e-9);
  EXPECT_LE(top, species_.height_m * (1 + species_.height_spread) + 1e-9);
  EXPECT_NEAR(tree().trunk().base().radius, result_.trunk_base_radius_m, 1e-12);
  EXPECT_GE(tree().trunk().base().radius, 0.02);
  EXPECT_LE(tree().trunk().base().radius, 0.08);
  // 4-6 levels, a few hundred to ~1500 branches, at most 10,000 nodes.
  EXPECT_GE(tree().MaxLevel(), 4);
  EXPECT_LE(tree().MaxLevel(), 6);
  EXPECT_GE(tree().size(), 150);
  EXPECT_LE(tree().size(), 1500);
  EXPECT_LE(tree().NodeCount(), 10000);
  // The reconstruction is scored on branches of radius >= 1 cm: the trunk and the main scaffold
  // (slender trees, so that their first frequency is the paper's: only a handful).
  int thick = 0;
  for (const Branch& b : tree().branches) thick += b.base().radius >= 0.01 ? 1 : 0;
  EXPECT_GE(thick, 5);
  // Not much scaling was needed to reach the height (node spacing stays what the species says).
  EXPECT_GT(result_.scale, 0.8);
  EXPECT_LT(result_.scale, 1.2);
}

TEST_P(EveryPreset, NodesAreEvenlySpacedAndEveryBranchHasThree) {
  double shortest = 1e9, longest = 0.0;
  for (const Branch& b : tree().branches) {
    ASSERT_GE(b.nodes.size(), 3u) << "branch " << b.id;
    for (size_t i = 1; i < b.nodes.size(); ++i) {
      const double d = (b.nodes[i].position - b.nodes[i - 1].position).norm();
      shortest = std::min(shortest, d);
      longest = std::max(longest, d);
    }
  }
  EXPECT_GE(shortest, 0.025);
  EXPECT_LE(longest, 0.085);
}

TEST_P(EveryPreset, NothingGrowsBelowTheGround) {
  EXPECT_GE(LowestNodeOffTheTrunk(tree()),
            GeneratorOptions{}.min_ground_clearance_m * result_.scale - 1e-9);
}

TEST_P(EveryPreset, BranchesBendSmoothly) {
  double worst = 0.0;
  for (const Branch& b : tree().branches) {
    for (size_t i = 1; i + 1 < b.nodes.size(); ++i) {
      worst = std::max(worst, AngleDeg(b.nodes[i].position - b.nodes[i - 1].position,
                                       b.nodes[i + 1].position - b.nodes[i].position));
    }
  }
  EXPECT_LT(worst, 20.0) << "largest turn between consecutive segments";
}

TEST_P(EveryPreset, RadiiFollowThePipeModel) {
  const double n = species_.pipe_exponent;
  const double tip = result_.tip_radius_m;
  const double floor = species_.min_twig_radius_m;
  const auto children = tree().Children();
  int forks_checked = 0;
  for (const Branch& b : tree().branches) {
    for (size_t i = 0; i < b.nodes.size(); ++i) {
      EXPECT_GE(b.nodes[i].radius, floor - 1e-15);
      if (i + 1 < b.nodes.size()) {
        EXPECT_GE(b.nodes[i].radius, b.nodes[i + 1].radius) << "branch " << b.id << " node " << i;
      }
    }
    if (!b.is_trunk()) {
      EXPECT_LE(b.base().radius, tree().branches[b.parent].nodes[b.parent_node].radius);
    }
    // r^n at a node = r^n of the next node + sum of the children's base r^n + the shed-shoot
    // term tip^n * shed * segment (a tip counts tip^n).
    std::map<int, double> child_sum;
    bool clamped = false;
    for (const int c : children[b.id]) {
      const Branch& child = tree().branches[c];
      child_sum[child.parent_node] += std::pow(child.base().radius, n);
      clamped = clamped || child.base().radius <= floor * (1 + 1e-12);
    }
    for (const auto& [node, sum] : child_sum) {
      const double r = b.nodes[node].radius;
      if (clamped || r <= floor * (1 + 1e-12)) continue;
      double expected = sum;
      if (node + 1 < static_cast<int>(b.nodes.size())) {
        if (b.nodes[node + 1].radius <= floor * (1 + 1e-12)) continue;
        const double segment = (b.nodes[node + 1].position - b.nodes[node].position).norm();
        expected += std::pow(b.nodes[node + 1].radius, n) +
                    std::pow(tip, n) * species_.shed_shoots_per_m * segment;
      } else {
        expected += std::pow(tip, n);  // the axis ends in the fork: its own tip counts
      }
      EXPECT_NEAR(std::pow(r, n), expected, 1e-9 * expected)
          << "branch " << b.id << " node " << node;
      ++forks_checked;
    }
  }
  EXPECT_GT(forks_checked, 50);
}

TEST_P(EveryPreset, BranchingAnglesStayInTheSpeciesRange) {
  constexpr double kCurvatureSlack = 8.0;  // the first segment bends a little off the bud
  for (const Branch& b : tree().branches) {
    if (b.is_trunk()) continue;
    const double angle =
        AngleDeg(FirstDirection(b), Tangent(tree().branches[b.parent], b.parent_node));
    double mean = species_.levels[b.level - 1].branching_angle_deg;
    double spread = species_.levels[b.level - 1].branching_angle_spread_deg;
    if (IsForkStem(tree(), species_, b)) {
      mean = species_.trunk.fork_angle_deg;
      spread = species_.trunk.fork_angle_spread_deg;
    }
    EXPECT_GE(angle, mean - spread - kCurvatureSlack) << "branch " << b.id;
    EXPECT_LE(angle, mean + spread + kCurvatureSlack) << "branch " << b.id;
  }
}

TEST_P(EveryPreset, ChildrenStartOnTheirParentsNodes) {
  for (const Branch& b : tree().branches) {
    if (b.is_trunk()) continue;
    ASSERT_LT(b.parent, b.id);
    EXPECT_EQ(b.base().position, tree().branches[b.parent].nodes[b.parent_node].position);
    EXPECT_EQ(b.level, tree().branches[b.parent].level + 1);
  }
}

TEST_P(EveryPreset, BranchesDoNotPierceEachOther) {
  // Two branches that are not attached to each other (not parent and child, not siblings on one
  // node) never come closer than the sum of their radii, away from their own bases.
  SegmentGrid grid(0.1);
  for (const Branch& b : tree().branches) {
    for (size_t i = 1; i < b.nodes.size(); ++i) {
      grid.Add({b.nodes[i - 1].position, b.nodes[i].position, b.nodes[i - 1].radius, b.id,
                static_cast<int>(i - 1)});
    }
  }
  auto related = [&](int a, int c) {
    const Branch &x = tree().branches[a], &y = tree().branches[c];
    return a == c || x.parent == c || y.parent == a ||
           (x.parent == y.parent && x.parent_node == y.parent_node) ||
           (x.parent >= 0 && tree().branches[x.parent].parent == c) ||
           (y.parent >= 0 && tree().branches[y.parent].parent == a);
  };
  int piercing = 0;
  for (const Branch& b : tree().branches) {
    for (size_t i = 2; i < b.nodes.size(); ++i) {
      const Node &p = b.nodes[i - 1], &q = b.nodes[i];
      grid.AnyNear(p.position, q.position, grid.max_radius() + p.radius, [&](const GridSegment& s) {
        if (related(b.id, s.branch)) return false;
        if (SegmentDistance(p.position, q.position, s.a, s.b) < p.radius + s.radius) ++piercing;
        return false;
      });
    }
  }
  // The clearance check works on estimated radii; allow a handful of touching twigs.
  EXPECT_LE(piercing, tree().size() / 100) << piercing << " piercing segment pairs";
}

TEST_P(EveryPreset, PhyllotaxisIsTheSpecies) {
  const auto children = tree().Children();
  const double jitter = species_.phyllotaxis_jitter_deg;
  int pairs = 0, lone = 0;
  double decussate_error = 0.0;
  int decussate_count = 0;
  for (const Branch& b : tree().branches) {
    std::map<int, std::vector<int>> at_node;
    for (const int c : children[b.id]) {
      if (!IsForkStem(tree(), species_, tree().branches[c])) {
        at_node[tree().branches[c].parent_node].push_back(c);
      }
    }
    const BudPattern& buds = b.is_trunk() ? species_.trunk.buds : species_.levels[b.level - 1].buds;
    const double segment = b.Length() / (b.nodes.size() - 1);
    int previous_node = -1;
    Vec3 previous_axis;
    for (const auto& [node, kids] : at_node) {
      if (species_.phyllotaxis == Phyllotaxis::kAlternate) {
        EXPECT_EQ(kids.size(), 1u) << "alternate buds: one child per node";
        continue;
      }
      ASSERT_LE(kids.size(), 2u) << "opposite buds: at most a pair per node";
      if (kids.size() == 1) {
        ++lone;
        previous_node = -1;
        continue;
      }
      ++pairs;
      const Vec3 a = Across(tree(), tree().branches[kids[0]]);
      const Vec3 c = Across(tree(), tree().branches[kids[1]]);
      // A pair leaves on opposite sides (180 degrees, each bud jittered).
      EXPECT_GE(AngleDeg(a, c), 180.0 - 2 * jitter - 12.0) << "branch " << b.id << " node " << node;
      // Decussate: the next node's pair turns 90 degrees (plus the axis twist and jitter).
      const Vec3 axis = (a - c).normalized();
      const double gap_nodes = (node - previous_node) * segment / buds.spacing_m;
      if (previous_node >= 0 && gap_nodes < 1.3) {
        const double turn = AngleDeg(axis, previous_axis);
        const double folded = std::min(turn, 180.0 - turn);  // axes have no sign
        decussate_error += std::abs(folded - 90.0);
        ++decussate_count;
      }
      previous_node = node;
      previous_axis = axis;
    }
  }
  if (species_.phyllotaxis == Phyllotaxis::kOpposite) {
    EXPECT_GT(pairs, 20);
    EXPECT_GT(decussate_count, 5);
    // Random pair directions would give a mean error of 45 degrees.
    EXPECT_LT(decussate_error / std::max(1, decussate_count), 25.0);
    std::printf("%s: %d pairs, %d lone buds, mean decussate error %.1f deg over %d\n",
                species_.name.c_str(), pairs, lone, decussate_error / std::max(1, decussate_count),
                decussate_count);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Synth, EveryPreset,
    ::testing::Values(Case{"acer_palmatum", 1}, Case{"acer_palmatum", 2}, Case{"acer_palmatum", 3},
                      Case{"magnolia", 1}, Case{"magnolia", 2}, Case{"magnolia", 3},
                      Case{"acer_rubrum", 1}, Case{"acer_rubrum", 2}, Case{"acer_rubrum", 3}),
    [](const ::testing::TestParamInfo<Case>& param_info) {
      return param_info.param.species + "_seed" + std::to_string(param_info.param.seed);
    });

TEST(TreeGenerator, SameSeedSameBytesOtherSeedOtherTree) {
  const std::filesystem::path dir = test::TempDir();
  const SpeciesParams p = SpeciesPreset("acer_rubrum");
  WriteTreeJson(GenerateTree(p, 7), dir / "a.json");
  WriteTreeJson(GenerateTree(p, 7), dir / "b.json");
  WriteTreeJson(GenerateTree(p, 8), dir / "c.json");
  const std::string a = test::ReadText(dir / "a.json");
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, test::ReadText(dir / "b.json"));
  EXPECT_NE(a, test::ReadText(dir / "c.json"));
  // The file reads back as the same tree.
  EXPECT_EQ(ReadTreeJson(dir / "a.json").size(), GenerateTree(p, 7).size());
}

// Longest path along the branches from the trunk base to a tip, from the tree alone.
double LongestPathToTip(const Tree& tree) {
  const auto path_to = [&](auto& self, int branch, int node) -> double {
    const Branch& b = tree.branches[branch];
    const double below = b.is_trunk() ? 0.0 : self(self, b.parent, b.parent_node);
    return below + b.ArcLengths()[node];
  };
  double longest = 0.0;
  for (const Branch& b : tree.branches) {
    longest = std::max(longest, path_to(path_to, b.id, static_cast<int>(b.nodes.size()) - 1));
  }
  return longest;
}

TEST(TreeGenerator, SizeKnobsMoveTheTree) {
  SpeciesParams p = SpeciesPreset("acer_rubrum");
  p.height_spread = 0.0;
  p.trunk_radius_spread = 0.0;
  p.height_m = 3.0;
  p.trunk_base_radius_m = 0.05;
  const TreeGenerationResult r = GrowTree(p, 3);
  EXPECT_NEAR(r.height_m, 3.0, 1e-12);
  // Elastic similarity on the longest path: a tree whose longest path is longest_path_ratio x
  // height_m has the species' trunk radius; a longer one is thicker as path^1.5.
  const double path = LongestPathToTip(r.tree);
  EXPECT_NEAR(r.longest_path_m, path, 1e-9);
  EXPECT_GT(path, 3.0);  // at least the height (the trunk rises from the ground)
  EXPECT_NEAR(r.tree.trunk().base().radius,
              0.05 * std::pow(path / (p.longest_path_ratio * 3.0), 1.5), 1e-12);
  // The same tree with twice the radius knob (growth does not depend on it but for the
  // clearance check's guess, which a zero clearance switches off).
  GeneratorOptions no_clearance;
  no_clearance.clearance_radii = 0.0;
  no_clearance.min_clearance_m = 0.0;
  const TreeGenerationResult thin = GrowTree(p, 3, no_clearance);
  p.trunk_base_radius_m = 0.1;
  const TreeGenerationResult thick = GrowTree(p, 3, no_clearance);
  EXPECT_EQ(thin.tree.size(), thick.tree.size());
  EXPECT_NEAR(thick.trunk_base_radius_m, 2 * thin.trunk_base_radius_m, 1e-12);
  // A species whose typical path is longer makes the same tree thinner.
  p.longest_path_ratio *= 2;
  EXPECT_NEAR(GrowTree(p, 3, no_clearance).trunk_base_radius_m,
              thick.trunk_base_radius_m / std::pow(2.0, 1.5), 1e-12);
}

TEST(TreeGenerator, BudgetsAreHonoured) {
  GeneratorOptions options;
  options.max_branches = 200;
  options.max_nodes = 2000;
  const TreeGenerationResult r = GrowTree(SpeciesPreset("acer_palmatum"), 1, options);
  EXPECT_LE(r.tree.size(), 200);
  EXPECT_LE(r.tree.NodeCount(), 2000);
  EXPECT_GT(r.dropped_budget, 0);
  EXPECT_TRUE(FindProblems(r.tree).empty());
}

TEST(TreeGenerator, ClearanceCheckRedrawsAndDrops) {
  // Without the check nothing is redrawn; with a huge clearance much is dropped.
  GeneratorOptions off;
  off.clearance_radii = 0.0;
  off.min_clearance_m = 0.0;
  const TreeGenerationResult free = GrowTree(SpeciesPreset("magnolia"), 2, off);
  EXPECT_EQ(free.redrawn_directions, 0);
  EXPECT_EQ(free.dropped_crowded, 0);
  GeneratorOptions strict;
  strict.min_clearance_m = 0.15;
  const TreeGenerationResult crowded = GrowTree(SpeciesPreset("magnolia"), 2, strict);
  EXPECT_GT(crowded.dropped_crowded, 10);
  EXPECT_LT(crowded.tree.size(), free.tree.size());
}

TEST(TreeGenerator, DroopingShootsStopAboveTheGround) {
  // acer_palmatum with twigs drooping hard (and a low fork): without the ground their tips would
  // grow far below it.
  SpeciesParams p = SpeciesPreset("acer_palmatum");
  p.trunk.length_fraction = 0.15;
  for (LevelParams& level : p.levels) level.shape.tropism_tip_per_m = -6.0;
  GeneratorOptions options;
  options.min_ground_clearance_m = 0.1;
  int stopped = 0;
  for (const uint64_t seed : {1, 2, 3}) {
    const TreeGenerationResult r = GrowTree(p, seed, options);
    EXPECT_TRUE(FindProblems(r.tree).empty()) << "seed " << seed;
    // At the clearance, up to the scale to the drawn height.
    EXPECT_GE(LowestNodeOffTheTrunk(r.tree), 0.1 * r.scale - 1e-9) << "seed " << seed;
    stopped += r.stopped_at_ground;
    // A stopped branch keeps its node spacing (the presets' 2.5-8.5 cm, here times the scale:
    // drooping tips lower the top) and at least 3 nodes.
    for (const Branch& b : r.tree.branches) {
      ASSERT_GE(b.nodes.size(), 3u);
      for (size_t i = 1; i < b.nodes.size(); ++i) {
        const double d = (b.nodes[i].position - b.nodes[i - 1].position).norm();
        EXPECT_GE(d, 0.025 * r.scale);
        EXPECT_LE(d, 0.085 * r.scale);
      }
    }
  }
  EXPECT_GT(stopped, 10);
  // At clearance 0 nothing goes below the ground either.
  options.min_ground_clearance_m = 0.0;
  EXPECT_GE(LowestNodeOffTheTrunk(GrowTree(p, 1, options).tree), 0.0);
}

TEST(TreeGenerator, BadInputsAreRefused) {
  SpeciesParams p = SpeciesPreset("magnolia");
  p.height_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(GenerateTree(p, 1), InputError);
  p = SpeciesPreset("magnolia");
  p.levels.clear();
  EXPECT_THROW(GenerateTree(p, 1), InputError);
  p = SpeciesPreset("magnolia");
  p.min_twig_radius_m = -0.001;
  EXPECT_THROW(GenerateTree(p, 1), InputError);
  GeneratorOptions options;
  options.max_branches = 0;
  EXPECT_THROW(GenerateTree(SpeciesPreset("magnolia"), 1, options), InputError);
  options = GeneratorOptions{};
  options.clearance_radii = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(GenerateTree(SpeciesPreset("magnolia"), 1, options), InputError);
  options = GeneratorOptions{};
  options.min_ground_clearance_m = -0.1;
  EXPECT_THROW(GenerateTree(SpeciesPreset("magnolia"), 1, options), InputError);
}

TEST(TreeGenerator, CustomSpeciesWithSixLevelsGrows) {
  SpeciesParams p = SpeciesPreset("acer_rubrum");
  p.levels.push_back(p.levels.back());
  p.levels[4].buds.break_probability = 0.3;
  const Tree tree = GenerateTree(p, 5);
  EXPECT_TRUE(FindProblems(tree).empty());
  EXPECT_LE(tree.MaxLevel(), 6);
  EXPECT_LE(tree.size(), 1500);
}

}  // namespace
}  // namespace simtree::synth
