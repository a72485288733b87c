#pragma once
// Species parameters of the procedural trees of the synthetic capture bench (docs/species.md):
// everything GenerateTree (tree_generator.h) needs to grow a small leafless tree of one species,
// and its wood for the FEM oracle. Three presets model the paper's trees (acer_palmatum, magnolia,
// acer_rubrum, winter, 2-5 m, four to six branching levels); a JSON file describes a custom
// species, whole or as changes over a preset ("base": "magnolia").
//
// How the tree is grown (tree_generator.h has the details). The trunk rises from the origin; along
// it, and along every branch, buds sit at botanical nodes `buds.spacing_m` apart (opposite pairs
// turned 90 degrees node to node for Acer, one bud per node turned 137.5 degrees for Magnolia); a
// bud grows into a child of the next level with `buds.break_probability`. A child leaves its
// parent at `branching_angle_deg` and is `length_ratio` times the parent's length remaining above
// it (level 1: times the tree height and a crown profile). Every axis bends smoothly: a few
// low-frequency waves (`bend_*`) and a tropism towards (positive) or away from (negative) the
// vertical. Radii follow the pipe model r_parent^n = sum r_child^n from the twigs down, scaled so
// the trunk base has the radius elastic similarity gives the finished tree (below).
//
// Size knobs and the first natural frequency. The tree sways like a tapered cantilever carrying
// its crown: f ~ r / L^2 sqrt(E / rho) (a uniform cantilever: f = 0.56 r / (2 L^2) sqrt(E / rho)).
// With the pipe model every radius scales with the trunk's. The trunk follows elastic similarity
// (McMahon and Kronauer 1976: a stem's diameter grows as the 1.5 power of its length to the
// farthest tip) on the finished tree's longest path from the base to a tip, P:
// r = trunk_base_radius_m (P / (longest_path_ratio height_m))^1.5. So a tree whose stems grew
// long (arching, low-forked) is thicker, and f ~ r / P^2 ~ P^-0.5 varies much less between seeds
// than with a radius drawn apart from the crown (acer_palmatum, seeds 1-30: f1 spread 1.35x
// instead of 1.75x). f rises linearly with trunk_base_radius_m (while no twig is held at
// min_twig_radius_m; held twigs add crown mass and lower it a little more), falls as
// 1 / height_m^2 (trunk_base_radius_m is the typical tree's at that height; between the trees of
// one species it falls as H^-0.5) and rises with sqrt(wood.youngs_modulus_pa /
// wood.density_kg_m3). Measured with the FEM oracle on seeds 1-30 (docs/species.md), the
// presets' first frequencies all sit inside the paper's Table IV ranges.

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "simtree/synth/detail/fem_model.h"
#include "simtree/synth/detail/wood.h"

namespace simtree::synth {

// How buds are arranged around an axis.
enum class Phyllotaxis {
  kOpposite,   // two buds per node, 180 degrees apart (Acer: decussate with a 90 degree divergence)
  kAlternate,  // one bud per node (Magnolia: spiral with a 137.5 degree divergence)
};

// A damping ratio measured at a frequency; two of them fix Rayleigh damping (wood.h).
struct DampingAnchor {
  double frequency_hz = 1.0;
  double damping_ratio = 0.03;
};

// Green (living, water-saturated) wood along the grain, as the FEM oracle uses it.
struct SpeciesWood {
  double youngs_modulus_pa = 8.0e9;
  double shear_modulus_pa = 0.5e9;
  double density_kg_m3 = 900.0;  // green density: wood, water and bark
  // Young wood is less stiff (wood.h): E and G fall as (r / mature_radius_m)^young_wood_exponent
  // below mature_radius_m (docs/synth.md: the rule and its source).
  double mature_radius_m = 0.02;
  double young_wood_exponent = 0.0;
  // Rayleigh damping C = alpha M + beta K meets both anchors; between them the modal damping
  // ratio dips (zeta(f) = alpha / (4 pi f) + beta pi f), outside it grows.
  std::array<DampingAnchor, 2> damping = {DampingAnchor{1.0, 0.04}, DampingAnchor{6.0, 0.04}};

  // E, G, density and the Rayleigh coefficients. Throws InputError when the anchors need a
  // negative coefficient.
  WoodProperties Properties() const;
};

// The shape of one axis (the trunk or a branch).
struct AxisShape {
  double node_spacing_m = 0.05;  // distance between polyline nodes (at least 2 segments per axis)
  // Low-frequency waviness: two sine waves of curvature in perpendicular planes, with random
  // phases and wavelengths within +-25% of this one; one half-wave turns the axis by about
  // bend_angle_deg.
  double bend_wavelength_m = 0.6;
  double bend_angle_deg = 10.0;
  // Tropism: curvature (rad/m) that turns the axis towards +Z (negative: towards -Z, drooping),
  // times the sine of its angle to the vertical; it varies linearly from base to tip.
  double tropism_base_per_m = 0.0;
  double tropism_tip_per_m = 0.0;
};

// Where buds sit along an axis and which of them grow into children (of the next level).
struct BudPattern {
  double spacing_m = 0.1;          // arc length between botanical nodes
  double break_probability = 0.5;  // chance that a bud grows into a branch
  // How much buds facing up or down (on a leaning axis) are suppressed: the break probability is
  // times (1 - lateral_preference |bud direction . Z|). Flat, layered sprays need it high.
  double lateral_preference = 0.0;
};

struct TrunkParams {
  // Length of the trunk axis over the tree height (a central leader: 0.8-0.95; a trunk that forks
  // into co-dominant stems: the fork height).
  double length_fraction = 0.9;
  double lean_deg = 4.0;             // largest tilt of the trunk base from vertical
  double clear_bole_fraction = 0.3;  // no branches on this lower share of the trunk
  // A trunk that ends in `fork_count` co-dominant stems (level 1; 0 = a leader to the top): they
  // leave its tip `fork_angle_deg` (+- spread) from its axis, evenly around it, and are
  // fork_length_ratio times the height left above the fork long.
  int fork_count = 0;
  double fork_angle_deg = 30.0;
  double fork_angle_spread_deg = 8.0;
  double fork_length_ratio = 1.1;
  AxisShape shape;
  BudPattern buds;  // buds of the level-1 laterals
};

// The branches of one level (levels[0] = level 1, the trunk's children).
struct LevelParams {
  // Angle between a child's first segment and its parent's tangent at the attachment.
  double branching_angle_deg = 45.0;
  double branching_angle_spread_deg = 10.0;  // uniform +- this
  // Length: length_ratio times the parent's length remaining above the attachment (level 1:
  // times the tree height and the crown profile), times (1 +- length_spread). With
  // remaining_length_weight w < 1 the parent length counted is L - w s (s: the attachment's arc
  // length), so children near the tip stay longer: 1 gives a cone of children, 0 a cylinder.
  double length_ratio = 0.5;
  double length_spread = 0.2;
  double remaining_length_weight = 1.0;
  double branching_start_fraction = 0.2;  // children only beyond this share of the branch
  AxisShape shape;
  BudPattern buds;  // buds of this level's children (unused on the last level)
};

struct SpeciesParams {
  std::string name;         // preset name or a custom one
  std::string description;  // what it is modelled on

  // Size. A tree's height H is drawn uniformly in height_m (1 +- height_spread) and the generated
  // tree is scaled to exactly that height. Its trunk base radius follows elastic similarity
  // (McMahon and Kronauer: diameter ~ length to the farthest tip^1.5) on its longest path P from
  // the base to a tip: trunk_base_radius_m (P / (longest_path_ratio height_m))^1.5, times
  // (1 +- trunk_radius_spread). Trees whose branches grew longer (taller, or arching further
  // out) are thicker, and their first frequency (~ r / P^2 ~ P^-0.5) varies little.
  double height_m = 3.5;
  double height_spread = 0.1;
  double trunk_base_radius_m = 0.04;  // of a tree whose longest path is the typical one
  double trunk_radius_spread = 0.05;
  // A typical tree's longest path from the trunk base to a twig tip, over its height (a central
  // leader: ~1.07; a low fork into arching stems: ~1.3).
  double longest_path_ratio = 1.1;
  double min_twig_radius_m = 0.002;  // radii never go below this (thinnest twig tips)

  // Pipe model: r_parent^n = sum r_child^n at every fork, n = pipe_exponent (da Vinci: 2;
  // measured on trees: 2-2.5). Between forks a branch thickens towards its base as if each metre
  // of it carried `shed_shoots_per_m` more twig tips (short shoots that died or fell).
  double pipe_exponent = 2.3;
  double shed_shoots_per_m = 2.0;

  Phyllotaxis phyllotaxis = Phyllotaxis::kOpposite;
  double divergence_angle_deg = 90.0;  // turn between successive nodes around the parent axis
  double phyllotaxis_jitter_deg = 10.0;

  // Crown profile: the length of a level-1 lateral as a share of the longest, against its
  // position t in the crown (0 at the clear bole, 1 at the trunk top): a bump that peaks
  // (value 1) at crown_peak_position, with steepness crown_sharpness (0: flat), above
  // crown_floor. A peak near 0 is a cone, near 0.4 an oval, near 1 a vase.
  double crown_peak_position = 0.3;
  double crown_sharpness = 2.0;
  double crown_floor = 0.2;

  double min_branch_length_m = 0.08;  // shorter children are not grown (buds that stay spurs)

  TrunkParams trunk;
  std::vector<LevelParams> levels;  // 4 to 6 branching levels below the trunk
  SpeciesWood wood;
  // How far the root plate gives under a sway (fem_model.h): its rotational stiffness over the
  // trunk base's E I / H. 0 clamps the base.
  double root_plate_stiffness_ratio = 0.0;

  int branching_levels() const { return static_cast<int>(levels.size()); }
};

// The FEM oracle's options for a tree of this species (its root plate; default meshing).
FemOptions SpeciesFemOptions(const SpeciesParams& params);

// The presets' names, in a fixed order.
std::vector<std::string> SpeciesPresetNames();
// A preset by name; throws InputError listing the names for an unknown one.
SpeciesParams SpeciesPreset(const std::string& name);

// Throws InputError naming `source` and the field (e.g. "levels[2].branching_angle_deg") when a
// value is not finite or out of its range, or the levels are not 4 to 6.
void ValidateSpecies(const SpeciesParams& params, const std::string& source);

// JSON: the whole struct ("format": "simtree.species", "version": 1), fields named as in C++.
nlohmann::ordered_json SpeciesToJson(const SpeciesParams& params);
// A whole description, or changes over a preset: {"base": "magnolia", "height_m": 3.0,
// "levels": [{}, {"branching_angle_deg": 60}]}. Objects merge field by field; `levels` merges
// element by element (the file's array gives the count; entries beyond the preset's count start
// from its last level). Strict: an unknown field, a wrong type or a value out of range throws
// InputError naming `source` and the field; without "base" every field is required.
SpeciesParams SpeciesFromJson(const nlohmann::json& doc, const std::string& source);
SpeciesParams ReadSpeciesJson(const std::filesystem::path& path);
// Validates, then writes atomically.
void WriteSpeciesJson(const SpeciesParams& params, const std::filesystem::path& path);

const char* ToString(Phyllotaxis phyllotaxis);

}  // namespace simtree::synth
