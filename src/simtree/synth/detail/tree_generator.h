#pragma once
// Procedural leafless trees for the synthetic capture bench: a species (species.h) and a seed in,
// a valid simtree Tree out (core/tree.h), the same tree for the same seed.
//
// How a tree grows, level by level (all branches of a level before any of the next):
//  1. The trunk rises from (0, 0, 0), leaning up to trunk.lean_deg, trunk.length_fraction of the
//     drawn height long. A trunk with fork_count >= 2 ends in that many co-dominant level-1
//     stems, evenly around its tip.
//  2. Along every axis of the level, buds sit at botanical nodes buds.spacing_m apart (random
//     phase, +-15%) from branching_start_fraction (the trunk: clear_bole_fraction) to the tip;
//     opposite phyllotaxis puts two buds 180 degrees apart per node, alternate one; node k turns
//     k x divergence_angle_deg around the parent axis (in a parallel-transported frame), plus a
//     random twist of up to phyllotaxis_jitter_deg per node (so decussate pairs do not stack in
//     four exact ranks) and as much jitter per bud. A bud breaks with buds.break_probability,
//     less when it faces up or down (lateral_preference). The buds of a node share one "vigour"
//     draw, so an opposite pair breaks together; the draws are stratified in blocks of four
//     nodes, so every axis gets close to its expected number of children (branch counts vary
//     little between seeds, and few long branches stay bare). Each bud snaps to the nearest
//     polyline node, so a child starts exactly on a node of its parent (no gap); both buds of an
//     opposite pair share the node.
//  3. A child leaves at branching_angle_deg +- spread from its parent's tangent there. Its length
//     is length_ratio x (parent length - remaining_length_weight x attachment arc length) (level
//     1: x the height x the crown profile) x (1 +- length_spread); shorter than
//     min_branch_length_m and it is not grown.
//  4. Its axis is integrated in small steps: two sine waves of curvature in perpendicular planes
//     (random phase, a few low-frequency bends: smooth, no zig-zag) plus tropism towards or away
//     from the vertical; nodes every node_spacing_m (at least 2 segments, so 3 nodes).
//  5. Clearance: each new axis is checked against every axis grown so far (a spatial hash of
//     segments, segment_grid.h); if it comes within clearance_radii x the sum of the two
//     estimated radii (and at least min_clearance_m) of one, its direction is drawn again (angle
//     and azimuth jitter), up to max_direction_tries times, then the bud is dropped. Near its own
//     base a child is not checked against its parent and the siblings on the same node until it
//     has left them at its branching angle. Radii are not known while growing (they come from the
//     finished tree), so the check estimates a base radius trunk radius x (length / height)^1.3
//     tapering to a quarter at the tip, with the trunk radius of a typical tree of the drawn
//     height, trunk_base_radius_m (H / height_m)^1.5 (+- trunk_radius_spread).
//  6. The ground: a drooping axis that would come down to within min_ground_clearance_m of the
//     ground stops at its last node above that (its tip does not grow into the ground); a
//     direction that leaves fewer than 3 nodes is drawn again, as a crowded one is (step 5).
//     Checked before the clearance test, on the unscaled tree (step 8 moves the clearance by the
//     few percent of its scale).
//  7. Budget: when a level's candidates would pass max_branches or max_nodes, its shortest
//     candidates are not grown (suppressed shoots).
//  8. The tree is scaled about the origin so its highest node is exactly the drawn height.
//  9. Radii: the pipe model from the tips down. Every tip counts 1, each metre of axis
//     shed_shoots_per_m more, a fork adds its children: P_node = P_next + shed x segment +
//     sum P_child, r = c P^(1/n), and never below min_twig_radius_m. c is chosen so the trunk
//     base has the radius of elastic similarity on the finished tree's longest path from the
//     base to a tip (species.h): the stem carries the crown it grew, not a drawn one. So r^n at a
//     fork is the sum of the children's r^n plus the continuing axis's r^n (to the shed-shoot
//     term), and radii grow monotonically to the base.
// 10. Levels (AssignLevels), frames (ComputeFrames), metadata, then ValidateTree.

#include <cstdint>
#include <vector>

#include "simtree/core/tree.h"
#include "simtree/synth/species.h"

namespace simtree::synth {

struct GeneratorOptions {
  int max_branches = 1500;
  int max_nodes = 10000;
  double clearance_radii = 2.0;
  double min_clearance_m = 0.012;
  int max_direction_tries = 6;
  double min_ground_clearance_m = 0.05;  // step 6
};

struct TreeGenerationResult {
  Tree tree;
  double height_m = 0.0;                // the drawn height, which the tree has exactly
  double trunk_base_radius_m = 0.0;     // the trunk base radius (step 9)
  double longest_path_m = 0.0;          // longest path from the trunk base to a tip (step 9)
  double scale = 1.0;                   // uniform scale applied in step 8
  double tip_radius_m = 0.0;            // c: radius of a lone tip before the min_twig_radius floor
  int redrawn_directions = 0;           // directions drawn again by the clearance check
  int dropped_crowded = 0;              // buds dropped after max_direction_tries
  int stopped_at_ground = 0;            // axes that stopped short at the ground (step 6)
  int dropped_budget = 0;               // candidates dropped by max_branches / max_nodes
  std::vector<int> branches_per_level;  // index = level
};

// Grows a tree of `species` from `seed` (deterministic). Throws InputError for invalid species
// parameters.
TreeGenerationResult GrowTree(const SpeciesParams& species, uint64_t seed,
                              const GeneratorOptions& options = {});

// GrowTree's tree: metadata species = species.name, source "synth <species> seed <seed>".
Tree GenerateTree(const SpeciesParams& species, uint64_t seed,
                  const GeneratorOptions& options = {});

}  // namespace simtree::synth
